"""Independent physics for the corpus19 problems, derived with SymPy.

Each system is built from Cartesian positions of its bodies in an inertial frame (or, for
rigid bodies, centre-of-mass velocity plus spin) and a potential energy, exactly as a
textbook derivation would do it.  From T and V we derive L = T - V, the momenta, the
Euler-Lagrange equations E_i = d/dt dL/dq_i' - dL/dq_i, the mass matrix, the energy
function h = sum q' dL/dq' - L, equilibria (by solving the generalized forces at rest) and
the linearized frequencies.

Coordinates are plain symbols: for a coordinate named `r`, the symbols r, r_d (velocity) and
r_dd (acceleration).  Time is `t`.  Nothing here depends on the lagrange tool.
"""
import sympy as sp

t = sp.Symbol('t', real=True)


class Coord:
    def __init__(self, name, periodic=False, domain=None):
        self.name = name
        self.periodic = periodic
        # domain: None (any real), 'positive', or (low, high) sympy expressions
        self.domain = domain
        pos = domain == 'positive'
        self.q = sp.Symbol(name, real=True, positive=True) if pos else sp.Symbol(name, real=True)
        self.qd = sp.Symbol(name + '_d', real=True)
        self.qdd = sp.Symbol(name + '_dd', real=True)


def P(name, **kw):
    """A physical parameter: positive unless told otherwise."""
    kw.setdefault('positive', True)
    return sp.Symbol(name, real=True, **kw)


class System:
    def __init__(self, sid, coords, params, T, V, assume=(), param_ranges=None, coord_ranges=None):
        self.id = sid
        self.coords = coords
        self.params = params  # dict name -> Symbol
        self.T = sp.simplify(T)
        self.V = sp.simplify(V)
        self.L = self.T - self.V
        self.assume = list(assume)  # sympy relations on parameters
        self.param_ranges = param_ranges or {}
        self.coord_ranges = coord_ranges or {}
        self.q = [c.q for c in coords]
        self.qd = [c.qd for c in coords]
        self.qdd = [c.qdd for c in coords]
        self._derive()

    # total time derivative of an expression of (q, q', t) (and q'' where present)
    def ddt(self, F):
        out = sp.diff(F, t)
        for c in self.coords:
            out += sp.diff(F, c.q) * c.qd + sp.diff(F, c.qd) * c.qdd
        return out

    def _derive(self):
        L = self.L
        self.momenta = {c.name: sp.simplify(sp.diff(L, c.qd)) for c in self.coords}
        self.EL = []
        for c in self.coords:
            e = self.ddt(sp.diff(L, c.qd)) - sp.diff(L, c.q)
            self.EL.append(sp.expand(e))
        n = len(self.coords)
        self.M = sp.Matrix(n, n, lambda i, j: sp.simplify(sp.diff(self.EL[i], self.qdd[j])))
        rest = [sp.simplify(self.EL[i] - sum(self.M[i, j] * self.qdd[j] for j in range(n))) for i in range(n)]
        self.f = sp.Matrix([-r for r in rest])  # M q'' = f
        sol = self.M.LUsolve(self.f)
        self.acc = {self.qdd[i]: sp.simplify(sol[i]) for i in range(n)}
        self.detM = sp.factor(sp.simplify(self.M.det()))
        self.h = sp.simplify(sum(qd * sp.diff(L, qd) for qd in self.qd) - L)

    def onshell(self, expr):
        """Substitute the true accelerations."""
        return expr.subs(self.acc)

    def generalized_force_at_rest(self):
        """Q_i(q) = -E_i at q' = 0, q'' = 0 (only meaningful without explicit t)."""
        sub = {v: 0 for v in self.qd + self.qdd}
        return [sp.simplify(-e.subs(sub)) for e in self.EL]

    def linearize(self, point):
        """M0 x'' + C0 x' + K0 x = 0 about an equilibrium `point` (dict coord symbol -> value)."""
        n = len(self.coords)
        E = sp.Matrix(self.EL)
        zero = {v: 0 for v in self.qd + self.qdd}
        M0 = sp.Matrix(n, n, lambda i, j: sp.diff(E[i], self.qdd[j]).subs(zero).subs(point))
        C0 = sp.Matrix(n, n, lambda i, j: sp.diff(E[i], self.qd[j]).subs(zero).subs(point))
        K0 = sp.Matrix(n, n, lambda i, j: sp.diff(E[i], self.q[j]).subs(zero).subs(point))
        return sp.simplify(M0), sp.simplify(C0), sp.simplify(K0)

    def omega2(self, point):
        """The eigenvalues w^2 of the linearized motion (x ~ e^{i w t}): det(K - w^2 M + i w C) = 0."""
        M0, C0, K0 = self.linearize(point)
        w = sp.Symbol('w')
        poly = sp.expand(sp.simplify((K0 - w**2 * M0 + sp.I * w * C0).det()))
        return poly, w

    def sym(self, name):
        for c in self.coords:
            if c.name == name:
                return c.q
        return self.params[name]


def speed2(pos, coords):
    v = []
    for x in pos:
        d = sp.diff(x, t)
        for c in coords:
            d += sp.diff(x, c.q) * c.qd
        v.append(d)
    return sum(vi**2 for vi in v)


def point_T(m, pos, coords):
    return sp.Rational(1, 2) * m * speed2(pos, coords)


# ----------------------------------------------------------------------------------------
SYSTEMS = {}


def register(s):
    SYSTEMS[s.id] = s
    return s


def build():
    half = sp.Rational(1, 2)

    # 1. spherical pendulum -----------------------------------------------------------
    th, ph = Coord('theta', True), Coord('phi', True)
    m, l, g = P('m'), P('l'), P('g')
    pos = [l * sp.sin(th.q) * sp.cos(ph.q), l * sp.sin(th.q) * sp.sin(ph.q), -l * sp.cos(th.q)]
    register(System('sph-pendulum', [th, ph], dict(m=m, l=l, g=g),
                    point_T(m, pos, [th, ph]), m * g * pos[2]))

    # 2. perturbed Kepler: V = -k/r + beta/r^2 -----------------------------------------
    r, ph = Coord('r', domain='positive'), Coord('phi', True)
    m, k, beta, a = P('m'), P('k'), P('beta'), P('a')
    pos = [r.q * sp.cos(ph.q), r.q * sp.sin(ph.q)]
    register(System('precessing-orbit', [r, ph], dict(m=m, k=k, beta=beta, a=a),
                    point_T(m, pos, [r, ph]), -k / r.q + beta / r.q**2))

    # 3. particle inside a cone, vertex down, half-angle alpha -------------------------
    rho, ph = Coord('rho', domain='positive'), Coord('phi', True)
    m, g, alpha, a = P('m'), P('g'), P('alpha'), P('a')
    pos = [rho.q * sp.cos(ph.q), rho.q * sp.sin(ph.q), rho.q * sp.cot(alpha)]
    register(System('cone-particle', [rho, ph], dict(m=m, g=g, alpha=alpha, a=a),
                    point_T(m, pos, [rho, ph]), m * g * pos[2]))

    # 4. bead on a rod turning in a vertical plane --------------------------------------
    r = Coord('r')
    m, g, w = P('m'), P('g'), P('omega')
    pos = [r.q * sp.cos(w * t), r.q * sp.sin(w * t)]
    register(System('rod-vertical', [r], dict(m=m, g=g, omega=w),
                    point_T(m, pos, [r]), m * g * pos[1]))

    # 5. elastic pendulum -----------------------------------------------------------------
    r, th = Coord('r', domain='positive'), Coord('theta', True)
    m, g, k, l0 = P('m'), P('g'), P('k'), P('l0')
    pos = [r.q * sp.sin(th.q), -r.q * sp.cos(th.q)]
    register(System('elastic-pendulum', [r, th], dict(m=m, g=g, k=k, l0=l0),
                    point_T(m, pos, [r, th]), m * g * pos[1] + half * k * (r.q - l0)**2,
                    assume=[k * l0 - m * g > 0]))

    # 6. bead on a horizontal hoop turning about a point of its rim --------------------
    th = Coord('theta', True)
    m, a, w = P('m'), P('a'), P('omega')
    pos = [a * sp.cos(w * t) + a * sp.cos(w * t + th.q), a * sp.sin(w * t) + a * sp.sin(w * t + th.q)]
    register(System('hoop-rim', [th], dict(m=m, a=a, omega=w), point_T(m, pos, [th]), sp.S(0)))

    # 7. pendulum whose support goes round a vertical circle ---------------------------
    th = Coord('theta', True)
    m, l, a, g, w = P('m'), P('l'), P('a'), P('g'), P('omega')
    pos = [a * sp.cos(w * t) + l * sp.sin(th.q), a * sp.sin(w * t) - l * sp.cos(th.q)]
    register(System('circling-support', [th], dict(m=m, l=l, a=a, g=g, omega=w),
                    point_T(m, pos, [th]), m * g * pos[1]))

    # 8. pendulum hanging from a cart on an incline -----------------------------------
    s, th = Coord('s'), Coord('theta', True)
    M, m, l, g, alpha = P('M'), P('m'), P('l'), P('g'), P('alpha')
    cart = [s.q * sp.cos(alpha), -s.q * sp.sin(alpha)]
    bob = [cart[0] + l * sp.sin(th.q), cart[1] - l * sp.cos(th.q)]
    register(System('incline-cart', [s, th], dict(M=M, m=m, l=l, g=g, alpha=alpha),
                    point_T(M, cart, [s, th]) + point_T(m, bob, [s, th]),
                    M * g * cart[1] + m * g * bob[1]))

    # 9. particle on a paraboloid z = c rho^2 --------------------------------------------
    rho, ph = Coord('rho', domain='positive'), Coord('phi', True)
    m, g, c, a = P('m'), P('g'), P('c'), P('a')
    pos = [rho.q * sp.cos(ph.q), rho.q * sp.sin(ph.q), c * rho.q**2]
    register(System('paraboloid', [rho, ph], dict(m=m, g=g, c=c, a=a),
                    point_T(m, pos, [rho, ph]), m * g * pos[2]))

    # 10. bead on a helix turning about its vertical axis ------------------------------
    ph = Coord('phi')
    m, g, R, b, W = P('m'), P('g'), P('R'), P('b'), P('Omega')
    pos = [R * sp.cos(ph.q + W * t), R * sp.sin(ph.q + W * t), b * ph.q]
    register(System('turning-helix', [ph], dict(m=m, g=g, R=R, b=b, Omega=W),
                    point_T(m, pos, [ph]), m * g * pos[2]))

    # 11. two masses joined through a hole in a table ----------------------------------
    r, ph = Coord('r', domain='positive'), Coord('phi', True)
    m1, m2, g, a, ell = P('m1'), P('m2'), P('g'), P('a'), P('ell')
    on_table = [r.q * sp.cos(ph.q), r.q * sp.sin(ph.q), 0]
    hanging = [0, 0, -(ell - r.q)]
    register(System('table-hole', [r, ph], dict(m1=m1, m2=m2, g=g, a=a),
                    point_T(m1, on_table, [r, ph]) + point_T(m2, hanging, [r, ph]),
                    m2 * g * hanging[2]))

    # 12. double Atwood machine -----------------------------------------------------------
    x, y = Coord('x'), Coord('y')
    m1, m2, m3, g, la, lb = P('m1'), P('m2'), P('m3'), P('g'), P('la'), P('lb')
    # depths below the fixed pulley (positive downward); heights are minus depths
    d1 = x.q
    dp = la - x.q            # the movable pulley
    d2 = dp + y.q
    d3 = dp + (lb - y.q)
    register(System('double-atwood', [x, y], dict(m1=m1, m2=m2, m3=m3, g=g),
                    point_T(m1, [-d1], [x, y]) + point_T(m2, [-d2], [x, y]) + point_T(m3, [-d3], [x, y]),
                    -g * (m1 * d1 + m2 * d2 + m3 * d3)))

    # 13. swinging Atwood machine -------------------------------------------------------
    r, th = Coord('r', domain='positive'), Coord('theta', True)
    M, m, g, ell = P('M'), P('m'), P('g'), P('ell')
    # pulleys: m hangs from a point at the origin, M on the other side at x = -d
    bob = [r.q * sp.sin(th.q), -r.q * sp.cos(th.q)]
    counter = [-1, -(ell - r.q)]
    register(System('swinging-atwood', [r, th], dict(M=M, m=m, g=g),
                    point_T(m, bob, [r, th]) + point_T(M, counter, [r, th]),
                    m * g * bob[1] + M * g * counter[1], assume=[M - m > 0]))

    # 14. disc rolling inside a fixed cylinder ------------------------------------------
    th = Coord('theta', True)
    m, R, a, g = P('m'), P('R'), P('a'), P('g')
    centre = [(R - a) * sp.sin(th.q), -(R - a) * sp.cos(th.q)]
    spin = -(R - a) / a * th.qd          # absolute angular velocity of the disc (rolling)
    T = point_T(m, centre, [th]) + half * (m * a**2 / 2) * spin**2
    register(System('disc-in-cylinder', [th], dict(m=m, R=R, a=a, g=g), T, m * g * centre[1],
                    assume=[R - a > 0]))

    # 15. particle in an anisotropic trap fixed in a rotating frame -------------------
    x, y = Coord('x'), Coord('y')
    m, kx, ky, W = P('m'), P('kx'), P('ky'), P('Omega')
    pos = [x.q * sp.cos(W * t) - y.q * sp.sin(W * t), x.q * sp.sin(W * t) + y.q * sp.cos(W * t)]
    register(System('rotating-frame-trap', [x, y], dict(m=m, kx=kx, ky=ky, Omega=W),
                    point_T(m, pos, [x, y]), half * kx * x.q**2 + half * ky * y.q**2,
                    assume=[kx - m * W**2 > 0, ky - m * W**2 > 0]))
    return SYSTEMS


build()

if __name__ == '__main__':
    for s in SYSTEMS.values():
        print('=' * 70)
        print(s.id)
        print('T =', s.T)
        print('V =', s.V)
        print('p =', s.momenta)
        for c, e in zip(s.coords, s.EL):
            print('EL[%s] =' % c.name, sp.factor(sp.simplify(e)))
        print('M =', s.M, ' det =', s.detM)
        print('acc =', s.acc)
        print('h =', s.h)
        print('has t:', s.L.has(t))
