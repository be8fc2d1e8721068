"""The systems of SymPy's physics.mechanics tests (and its models module) that lagrange can
express with a Lagrangian, each built the SymPy way: frames, points, particles and
`sympy.physics.mechanics.Lagrangian`, or the Lagrangian written as SymPy's tests write it.

Each entry: name, the SymPy test or model it comes from, coordinates (dynamicsymbols),
the Lagrangian, parameter values, holonomic and nonholonomic constraints, and forces
(a list of (point or frame, vector) as LagrangesMethod takes them).
"""
import sympy as sm
import sympy.physics.mechanics as me

t = me.dynamicsymbols._t


def system(name, source, q, L, params, hol=(), nonhol=(), forces=(), frame=None):
    return dict(name=name, source=source, q=list(q), L=L, params=params,
                hol=list(hol), nonhol=list(nonhol), forces=list(forces), frame=frame)


def particle_lagrangian(N, pairs, potential):
    """L from particles (mass, position vector from the origin in N) and a potential."""
    O = me.Point("O")
    O.set_vel(N, 0)
    parts = []
    for k, (m, r) in enumerate(pairs):
        P = O.locatenew(f"P{k}", r)
        P.set_vel(N, r.dt(N))
        pa = me.Particle(f"pa{k}", P, m)
        pa.potential_energy = 0
        parts.append(pa)
    return me.Lagrangian(N, *parts) - potential


def simple_pendulum():
    m, l, g = sm.symbols("m l g")
    th = me.dynamicsymbols("theta")
    N = me.ReferenceFrame("N")
    r = l * sm.sin(th) * N.x - l * sm.cos(th) * N.y
    L = particle_lagrangian(N, [(m, r)], -m * g * l * sm.cos(th))
    return system("simple-pendulum", "test_lagrange.py::test_simp_pen", [th], L,
                  dict(m=1.3, l=0.7, g=9.81))


def n_pendulum(n, source):
    ths = me.dynamicsymbols(f"theta1:{n + 1}")
    ms = sm.symbols(f"m1:{n + 1}")
    ls = sm.symbols(f"l1:{n + 1}")
    g = sm.Symbol("g")
    N = me.ReferenceFrame("N")
    r = 0 * N.x
    pairs, V = [], 0
    for th, m, l in zip(ths, ms, ls):
        r = r + l * sm.sin(th) * N.x - l * sm.cos(th) * N.y
        pairs.append((m, r))
        V += m * g * r.dot(N.y)
    params = {str(s): v for s, v in zip(ms + ls, [1.0, 0.8, 1.7, 0.6, 1.1, 0.9][: n] + [1.0, 0.5, 0.75][: n])}
    params.update({str(l): 0.4 + 0.3 * k for k, l in enumerate(ls)})
    params["g"] = 9.81
    return system(f"pendulum-{n}-link", source, ths, particle_lagrangian(N, pairs, V), params)


def cartesian_pendulum():
    m, l, g = sm.symbols("m l g")
    x, y = me.dynamicsymbols("x y")
    N = me.ReferenceFrame("N")
    L = particle_lagrangian(N, [(m, x * N.x + y * N.y)], m * g * y)
    return system("cartesian-pendulum", "test_lagrange.py::test_nonminimal_pendulum", [x, y], L,
                  dict(m=1.0, l=2.0, g=9.81), hol=[x**2 + y**2 - l**2])


def disc_on_incline():
    m, g, R, l, alpha = sm.symbols("m g R l alpha")
    y, th = me.dynamicsymbols("y theta")
    # The disc's centre at distance y down the incline, spinning at theta'; I = m R^2/2.
    T = m * y.diff(t) ** 2 / 2 + m * R**2 * th.diff(t) ** 2 / 4
    V = m * g * (l - y) * sm.sin(alpha)
    L = T - V
    return system("disc-on-incline", "test_lagrange.py::test_rolling_disc (disc on an incline)",
                  [y, th], L, dict(m=2.0, g=9.81, R=0.3, l=5.0, alpha=0.4),
                  hol=[y - R * th])


def rolling_disc_plane():
    m, R, I, J = sm.symbols("m R I J")
    x, y, th, ph = me.dynamicsymbols("x y theta phi")
    T = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 + I * th.diff(t) ** 2 / 2 + J * ph.diff(t) ** 2 / 2
    return system("rolling-disc-plane", "test_lagrange.py::test_rolling_disc (upright, two rolling conditions)",
                  [x, y, th, ph], T, dict(m=1.5, R=0.4, I=0.06, J=0.12),
                  nonhol=[x.diff(t) - R * sm.cos(th) * ph.diff(t), y.diff(t) - R * sm.sin(th) * ph.diff(t)])


def spring_chain(n, fixed_right, source):
    xs = me.dynamicsymbols(f"x1:{n + 1}")
    ms = sm.symbols(f"m1:{n + 1}")
    ks = sm.symbols(f"k1:{n + 2}")
    T = sum(m * x.diff(t) ** 2 for m, x in zip(ms, xs)) / 2
    V = ks[0] * xs[0] ** 2 / 2
    for i in range(1, n):
        V += ks[i] * (xs[i] - xs[i - 1]) ** 2 / 2
    if fixed_right:
        V += ks[n] * xs[-1] ** 2 / 2
    params = {str(m): 1.0 + 0.3 * i for i, m in enumerate(ms)}
    params.update({str(k): 2.0 + 0.7 * i for i, k in enumerate(ks[: n + (1 if fixed_right else 0)])})
    return system(f"spring-chain-{n}{'-fixed' if fixed_right else ''}", source, xs, T - V, params)


def damped_oscillator():
    m, k, c = sm.symbols("m k c")
    x = me.dynamicsymbols("x")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    P = O.locatenew("P", x * N.x)
    P.set_vel(N, x.diff(t) * N.x)
    L = m * x.diff(t) ** 2 / 2 - k * x**2 / 2
    return system("spring-mass-damper", "test_kane.py::test_one_dof (mass-spring-damper)", [x], L,
                  dict(m=1.2, k=3.0, c=0.4), forces=[(P, -c * x.diff(t) * N.x)], frame=N)


def two_dof_damped():
    m, c1, c2, k1, k2 = sm.symbols("m c1 c2 k1 k2")
    q1, q2 = me.dynamicsymbols("q1 q2")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    P1 = O.locatenew("P1", q1 * N.x)
    P1.set_vel(N, q1.diff(t) * N.x)
    P2 = P1.locatenew("P2", q2 * N.x)
    P2.set_vel(N, (q1 + q2).diff(t) * N.x)
    L = m * q1.diff(t) ** 2 / 2 + m * (q1 + q2).diff(t) ** 2 / 2 - k1 * q1**2 / 2 - k2 * q2**2 / 2
    forces = [(P1, -c1 * q1.diff(t) * N.x + c2 * q2.diff(t) * N.x), (P2, -c2 * q2.diff(t) * N.x)]
    return system("two-dof-spring-damper", "test_kane.py::test_two_dof", [q1, q2], L,
                  dict(m=1.0, c1=0.3, c2=0.2, k1=4.0, k2=2.5), forces=forces, frame=N)


def cart_pendulum(links):
    M, g = sm.symbols("M g")
    x = me.dynamicsymbols("x")
    ths = me.dynamicsymbols(f"theta1:{links + 1}")
    ms = sm.symbols(f"m1:{links + 1}")
    ls = sm.symbols(f"l1:{links + 1}")
    N = me.ReferenceFrame("N")
    r = x * N.x
    pairs, V = [(M, r)], 0
    for th, m, l in zip(ths, ms, ls):
        r = r + l * sm.sin(th) * N.x + l * sm.cos(th) * N.y
        pairs.append((m, r))
        V += m * g * r.dot(N.y)
    params = dict(M=2.0, g=9.81)
    params.update({str(m): 0.5 + 0.25 * i for i, m in enumerate(ms)})
    params.update({str(l): 1.0 - 0.2 * i for i, l in enumerate(ls)})
    return system(f"cart-pendulum-{links}", "models.py::n_link_pendulum_on_cart", [x, *ths],
                  particle_lagrangian(N, pairs, V), params)


def rotating_frame_particle():
    m, W, k = sm.symbols("m W k")
    x, y = me.dynamicsymbols("x y")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", [W * t, N.z])
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", x * B.x + y * B.y)
    P.set_vel(N, P.pos_from(O).dt(N))
    pa = me.Particle("pa", P, m)
    L = me.Lagrangian(N, pa) - k * (x**2 + y**2) / 2
    return system("particle-in-rotating-frame", "test_particle.py / rotating frame (B.orientnew Axis W*t)",
                  [x, y], L, dict(m=1.0, W=0.7, k=4.0))


def central_force():
    m, k = sm.symbols("m k")
    r, ph = me.dynamicsymbols("r phi")
    N = me.ReferenceFrame("N")
    L = particle_lagrangian(N, [(m, r * sm.cos(ph) * N.x + r * sm.sin(ph) * N.y)], -k / r)
    return system("central-force-kepler", "test_lagrange.py (particle, central potential)", [r, ph], L,
                  dict(m=1.0, k=2.0))


def spherical_pendulum():
    m, l, g = sm.symbols("m l g")
    th, ph = me.dynamicsymbols("theta phi")
    N = me.ReferenceFrame("N")
    r = l * (sm.sin(th) * sm.cos(ph) * N.x + sm.sin(th) * sm.sin(ph) * N.y - sm.cos(th) * N.z)
    L = particle_lagrangian(N, [(m, r)], -m * g * l * sm.cos(th))
    return system("spherical-pendulum", "test_lagrange.py (spherical pendulum)", [th, ph], L,
                  dict(m=0.9, l=1.3, g=9.81))


def elastic_pendulum():
    m, k, l0, g = sm.symbols("m k l0 g")
    r, th = me.dynamicsymbols("r theta")
    N = me.ReferenceFrame("N")
    L = particle_lagrangian(N, [(m, r * sm.sin(th) * N.x - r * sm.cos(th) * N.y)],
                            k * (r - l0) ** 2 / 2 - m * g * r * sm.cos(th))
    return system("elastic-pendulum", "test_lagrange.py (spring pendulum)", [r, th], L,
                  dict(m=0.5, k=20.0, l0=1.0, g=9.81))


def driven_pendulum():
    m, l, g, a, w = sm.symbols("m l g a w")
    th = me.dynamicsymbols("theta")
    N = me.ReferenceFrame("N")
    r = l * sm.sin(th) * N.x + (a * sm.cos(w * t) - l * sm.cos(th)) * N.y
    L = particle_lagrangian(N, [(m, r)], m * g * r.dot(N.y))
    return system("pendulum-driven-support", "test_lagrange.py (moving support, explicit t)", [th], L,
                  dict(m=1.0, l=1.0, g=9.81, a=0.1, w=30.0))


def bead_on_hoop():
    m, R, g, W = sm.symbols("m R g W")
    th = me.dynamicsymbols("theta")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", [W * t, N.y])
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", R * sm.sin(th) * B.x - R * sm.cos(th) * B.y)
    P.set_vel(N, P.pos_from(O).dt(N))
    L = me.Lagrangian(N, me.Particle("pa", P, m)) + m * g * R * sm.cos(th)
    return system("bead-on-rotating-hoop", "test_lagrange.py (rotating hoop)", [th], L,
                  dict(m=0.3, R=0.8, g=9.81, W=5.0))


def double_atwood():
    m1, m2, m3, g = sm.symbols("m1 m2 m3 g")
    x, y = me.dynamicsymbols("x y")
    T = (m1 * x.diff(t) ** 2 + m2 * (y.diff(t) - x.diff(t)) ** 2 + m3 * (x.diff(t) + y.diff(t)) ** 2) / 2
    V = -m1 * g * x - m2 * g * (y - x) - m3 * g * (-x - y)
    return system("double-atwood", "test_lagrange.py (pulleys)", [x, y], T - V,
                  dict(m1=3.0, m2=1.0, m3=1.5, g=9.81))


def heavy_top():
    I1, I3, m, g, l = sm.symbols("I1 I3 m g l")
    th, ph, ps = me.dynamicsymbols("theta phi psi")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Body", [ph, th, ps], "313")
    w = B.ang_vel_in(N)
    T = (I1 * (w.dot(B.x) ** 2 + w.dot(B.y) ** 2) + I3 * w.dot(B.z) ** 2) / 2
    L = sm.simplify(T) - m * g * l * sm.cos(th)
    return system("heavy-symmetric-top", "test_rigidbody.py (Euler angles, 313)", [th, ph, ps], L,
                  dict(I1=0.3, I3=0.1, m=1.0, g=9.81, l=0.5))


def charged_particle():
    m, qe, Bz = sm.symbols("m qe Bz")
    x, y = me.dynamicsymbols("x y")
    # Symmetric gauge: A = Bz/2 (-y, x); L = T + q v·A.
    L = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 + qe * Bz * (x * y.diff(t) - y * x.diff(t)) / 2
    return system("charged-particle-magnetic-field", "test_lagrange.py (velocity-dependent potential)",
                  [x, y], L, dict(m=1.0, qe=0.5, Bz=2.0))


def coupled_pendula():
    m, l, g, k = sm.symbols("m l g k")
    a, b = me.dynamicsymbols("a b")
    T = m * l**2 * (a.diff(t) ** 2 + b.diff(t) ** 2) / 2
    V = -m * g * l * (sm.cos(a) + sm.cos(b)) + k * l**2 * (sm.sin(a) - sm.sin(b)) ** 2 / 2
    return system("coupled-pendula", "test_linearize.py (two pendula and a spring)", [a, b], T - V,
                  dict(m=1.0, l=1.0, g=9.81, k=2.0))


def block_on_wedge():
    m, M, g, al = sm.symbols("m M g alpha")
    X, s = me.dynamicsymbols("X s")
    N = me.ReferenceFrame("N")
    rw = X * N.x
    rb = (X + s * sm.cos(al)) * N.x - s * sm.sin(al) * N.y
    L = particle_lagrangian(N, [(M, rw), (m, rb)], -m * g * s * sm.sin(al))
    return system("block-on-sliding-wedge", "test_lagrange.py (wedge on a frictionless floor)", [X, s], L,
                  dict(m=1.0, M=3.0, g=9.81, alpha=0.5))


def all_systems():
    return [
        simple_pendulum(),
        n_pendulum(2, "test_lagrange.py::test_dub_pen"),
        n_pendulum(3, "models.py::n_link_pendulum (3 links)"),
        cartesian_pendulum(),
        disc_on_incline(),
        rolling_disc_plane(),
        spring_chain(1, False, "models.py::multi_mass_spring_damper (1 mass)"),
        spring_chain(2, True, "test_lagrange.py (two masses, three springs)"),
        spring_chain(3, False, "models.py::multi_mass_spring_damper (3 masses)"),
        damped_oscillator(),
        two_dof_damped(),
        cart_pendulum(1),
        cart_pendulum(2),
        rotating_frame_particle(),
        central_force(),
        spherical_pendulum(),
        elastic_pendulum(),
        driven_pendulum(),
        bead_on_hoop(),
        double_atwood(),
        heavy_top(),
        charged_particle(),
        coupled_pendula(),
        block_on_wedge(),
    ]
