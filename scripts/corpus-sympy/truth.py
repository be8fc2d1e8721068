"""The true answer of every part, derived from physics.py (never from the TOML files).

Equilibria are found by solving the generalized forces at rest and reducing angles into
(-pi, pi]; their stability from the linearized motion M x'' + C x' + K x = 0; frequencies as
the roots of det(K - w^2 M + i w C) = 0.  Steady motions from the equations with the
coordinate of `at` fixed and the cyclic angle turning uniformly.
"""
import sympy as sp
from physics import SYSTEMS, t

ANY = sp.Symbol('ANY')  # marker for "coordinate = any"


def S(sid):
    return SYSTEMS[sid]


def _stability_1dof(s, point):
    M0, C0, K0 = s.linearize(point)
    k = sp.simplify(K0[0, 0] / M0[0, 0])
    return k


def derive_equilibria():
    """Returns dict sid -> list of (point dict name->value, stability) with proofs printed."""
    eq = {}
    proofs = []

    # hoop-rim: Q = -m a^2 w^2 sin(theta)
    s = S('hoop-rim')
    Q = s.generalized_force_at_rest()[0]
    th = s.q[0]
    sols = sp.solve(sp.Eq(Q, 0), th)
    proofs.append(('hoop-rim', Q, sols))
    pts = []
    for v in [sp.S(0), sp.pi]:
        assert sp.simplify(Q.subs(th, v)) == 0
        k = _stability_1dof(s, {th: v})
        pts.append(({'theta': v}, 'stable' if sp.simplify(k).is_positive else 'unstable'))
    assert {sp.nsimplify(x) for x in sols} <= {0, sp.pi}, sols
    eq['hoop-rim'] = pts

    # disc-in-cylinder
    s = S('disc-in-cylinder')
    Q = s.generalized_force_at_rest()[0]
    th = s.q[0]
    R, a = s.params['R'], s.params['a']
    d = sp.Symbol('d', positive=True)
    pts = []
    for v in [sp.S(0), sp.pi]:
        assert sp.simplify(Q.subs(th, v)) == 0
        k = sp.simplify(_stability_1dof(s, {th: v}).subs(R, a + d))
        pts.append(({'theta': v}, 'stable' if k.is_positive else 'unstable'))
    assert set(sp.solve(sp.Eq(sp.simplify(Q.subs(R, a + d)), 0), th)) <= {0, sp.pi}
    eq['disc-in-cylinder'] = pts

    # elastic pendulum: Q_theta = -m g r sin(theta) => sin(theta) = 0 (r > 0);
    # Q_r = m g cos(theta) - k (r - l0) => r = l0 + m g cos(theta)/k
    s = S('elastic-pendulum')
    Qr, Qt = s.generalized_force_at_rest()
    r, th = s.q
    m, g, k, l0 = [s.params[n] for n in ('m', 'g', 'k', 'l0')]
    pts = []
    for v in [sp.S(0), sp.pi]:
        rv = sp.solve(sp.Eq(Qr.subs(th, v), 0), r)
        assert len(rv) == 1
        rv = rv[0]
        assert sp.simplify(Qt.subs({th: v, r: rv})) == 0
        poly, w = s.omega2({r: rv, th: v})
        lam = sp.Symbol('lam')
        roots = sp.solve(sp.expand(poly).subs(w**2, lam), lam)
        # under k l0 > m g: positive iff stable
        e = sp.Symbol('e', positive=True)
        roots = [sp.simplify(x.subs(k, (m * g + e) / l0)) for x in roots]
        stable = all(x.is_positive for x in roots)
        pts.append(({'r': rv, 'theta': v}, 'stable' if stable else 'unstable'))
        proofs.append(('elastic', v, rv, roots))
    eq['elastic-pendulum'] = pts

    # precessing orbit: Q_r = -dV/dr = -k/r^2 + 2 beta/r^3 ; Q_phi = 0 (phi free)
    s = S('precessing-orbit')
    Qr, Qp = s.generalized_force_at_rest()
    r, ph = s.q
    k, beta, m = s.params['k'], s.params['beta'], s.params['m']
    assert Qp == 0
    rv = sp.solve(sp.Eq(Qr, 0), r)
    assert rv == [2 * beta / k], rv
    M0, C0, K0 = s.linearize({r: rv[0], ph: 0})
    assert K0[1, 1] == 0 and K0[0, 1] == 0 and K0[1, 0] == 0
    assert sp.simplify(K0[0, 0]).is_positive
    eq['precessing-orbit'] = [({'r': rv[0], 'phi': ANY}, 'stable')]

    # rotating frame trap: Q = (-(kx - m W^2) x, -(ky - m W^2) y) => origin only
    s = S('rotating-frame-trap')
    Qx, Qy = s.generalized_force_at_rest()
    x, y = s.q
    sols = sp.solve([Qx, Qy], [x, y], dict=True)
    assert sols == [{x: 0, y: 0}], sols
    eq['rotating-frame-trap'] = [({'x': sp.S(0), 'y': sp.S(0)}, 'stable')]

    # no equilibrium: the generalized force at rest never vanishes in the domain
    for sid, why in [('cone-particle', 'Q_rho = -m g cot(alpha) != 0'),
                     ('table-hole', 'Q_r = -m2 g != 0'),
                     ('swinging-atwood', 'Q_r = -g (M - m cos theta) < 0 as M > m'),
                     ('incline-cart', 'Q_s = (M + m) g sin(alpha) != 0'),
                     ('turning-helix', 'Q_phi = -m g b != 0')]:
        Q = S(sid).generalized_force_at_rest()
        proofs.append((sid, Q, why))
        eq[sid] = []
    return eq, proofs


def derive_frequencies():
    out = {}
    w = None

    def roots_w(s, point):
        poly, w = s.omega2(point)
        lam = sp.Symbol('lam')
        p = sp.expand(poly)
        if p.has(w) and not sp.expand(p.subs(w, -w) - p) == 0:
            raise ValueError('odd powers of w')
        lams = sp.solve(p.subs(w**2, lam), lam) if p.has(w) else []
        # multiplicity
        P = sp.Poly(p.subs(w**2, lam), lam)
        res = []
        for rt, mult in sp.roots(P).items():
            res += [sp.simplify(rt)] * mult
        return res

    s = S('hoop-rim')
    out[('hoop-rim', 'frequencies')] = [sp.sqrt(l) for l in roots_w(s, {s.q[0]: 0})]
    s = S('disc-in-cylinder')
    out[('disc-in-cylinder', 'frequencies')] = [sp.sqrt(l) for l in roots_w(s, {s.q[0]: 0})]
    s = S('elastic-pendulum')
    m, g, k, l0 = [s.params[n] for n in ('m', 'g', 'k', 'l0')]
    out[('elastic-pendulum', 'frequencies')] = [sp.sqrt(l) for l in roots_w(s, {s.q[0]: l0 + m * g / k, s.q[1]: 0})]
    s = S('precessing-orbit')
    k, beta = s.params['k'], s.params['beta']
    out[('precessing-orbit', 'frequencies')] = [sp.sqrt(l) for l in roots_w(s, {s.q[0]: 2 * beta / k, s.q[1]: 0})]
    s = S('rotating-frame-trap')
    lams = roots_w(s, {s.q[0]: 0, s.q[1]: 0})
    out[('rotating-frame-trap', 'omega-squared')] = lams
    out[('rotating-frame-trap', 'frequencies')] = [sp.sqrt(l) for l in lams]
    return out


def derive_steady():
    """phi'^2 for a uniform rotation with the other coordinate fixed at `a`."""
    out = {}
    for sid, cname in [('precessing-orbit', 'r'), ('cone-particle', 'rho'), ('paraboloid', 'rho'),
                       ('table-hole', 'r')]:
        s = S(sid)
        i = [c.name for c in s.coords].index(cname)
        a = s.params['a']
        W2 = sp.Symbol('W2', positive=True)
        sub = {s.q[i]: a, s.qd[i]: 0, s.qdd[i]: 0}
        j = 1 - i
        sub.update({s.qdd[j]: 0})
        eqs = [sp.expand(e.subs(sub)).subs(s.qd[j]**2, W2) for e in s.EL]
        # the cyclic equation is identically 0; the other gives phi'^2
        assert sp.simplify(eqs[j]) == 0
        sol = sp.solve(eqs[i], W2)
        assert len(sol) == 1
        out[(sid, 'steady')] = sp.simplify(sol[0])
    return out


EQUILIBRIA, PROOFS = derive_equilibria()
FREQS = derive_frequencies()
STEADY = derive_steady()

if __name__ == '__main__':
    for k, v in EQUILIBRIA.items():
        print('equilibria', k, v)
    for p in PROOFS:
        print('  proof', p)
    for k, v in FREQS.items():
        print('freq', k, v)
    for k, v in STEADY.items():
        print('steady', k, v)
