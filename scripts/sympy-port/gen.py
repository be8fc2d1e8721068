"""Writes tests/sympy/*.json: for each system of systems.py, the Lagrangian in lagrange's
syntax, the coordinates, constraints and generalized forces, parameter values, and a few
seeded states (on the constraints) with SymPy's accelerations there, from
sympy.physics.mechanics.LagrangesMethod solved at 30 digits.

    python3 scripts/sympy-port/gen.py            # from the repository root
"""
import json
import os
import random
import sys

import sympy as sm
import sympy.physics.mechanics as me

sys.path.insert(0, os.path.dirname(__file__))
from systems import all_systems, t  # noqa: E402

STATES = 3
DIGITS = 30
OUT = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "sympy")


def text(expr, qs):
    """An expression of q(t), q'(t), t in lagrange's syntax (x, x', t; ^ for powers)."""
    rep = {}
    for q in qs:
        name = q.func.__name__
        rep[q.diff(t)] = sm.Symbol(name + "'")
    expr = expr.subs(rep)
    expr = expr.subs({q: sm.Symbol(q.func.__name__) for q in qs})
    return sm.sstr(expr).replace("**", "^")


def generalized_forces(s):
    """Q_i = sum over forces of F . (d v / d q_i') (what LagrangesMethod computes)."""
    if not s["forces"]:
        return None
    N = s["frame"]
    qs = s["q"]
    out = []
    for q in qs:
        total = 0
        for point, force in s["forces"]:
            v = point.vel(N)
            total += force.dot(v.diff(q.diff(t), N))
        out.append(sm.simplify(total))
    return out


def project(s, subs_par, rng):
    """A random state on the constraints: q onto the holonomic ones (Newton, minimum norm),
    then q' onto the velocity constraints (least change)."""
    qs = s["q"]
    n = len(qs)
    q = sm.Matrix([rng.uniform(-1, 1) for _ in qs])
    if s["name"] in ("central-force-kepler", "elastic-pendulum"):
        q[0] = 1 + abs(q[0])
    qd = sm.Matrix([rng.uniform(-1, 1) for _ in qs])
    tv = sm.Float(rng.uniform(0, 1), DIGITS)
    qsym = sm.symbols(f"z0:{n}")
    vsym = sm.symbols(f"v0:{n}")
    to_plain = {**{x.diff(t): v for x, v in zip(qs, vsym)}, **{x: z for x, z in zip(qs, qsym)}}
    hol = [sm.sympify(h).subs(subs_par).subs(to_plain) for h in s["hol"]]
    if hol:
        F = sm.Matrix(hol)
        J = F.jacobian(qsym)
        for _ in range(60):
            at = dict(zip(qsym, q))
            at[t] = tv
            f = F.subs(at).evalf(DIGITS)
            if max(abs(x) for x in f) < sm.Float(10) ** (-(DIGITS - 5)):
                break
            j = J.subs(at).evalf(DIGITS)
            q = q - j.T * (j * j.T).LUsolve(f)
    vel = [sm.diff(sm.sympify(h).subs(subs_par), t) for h in s["hol"]]
    vel += [sm.sympify(c).subs(subs_par) for c in s["nonhol"]]
    if vel:
        C = sm.Matrix([c.subs(to_plain) for c in vel])
        A = C.jacobian(vsym)
        at = {**dict(zip(qsym, q)), t: tv}
        a = A.subs(at).evalf(DIGITS)
        c = C.subs(at).subs(dict(zip(vsym, qd))).evalf(DIGITS)
        qd = qd - a.T * (a * a.T).LUsolve(c)
    return q, qd, tv


def accelerations(lm, s, q, qd, tv, subs_par):
    n = len(s["q"])
    at = {}
    for x, v, dv in zip(s["q"], q, qd):
        at[x.diff(t)] = dv
    for x, v in zip(s["q"], q):
        at[x] = v
    M = lm.mass_matrix_full.subs(subs_par).subs(at).subs(t, tv).evalf(DIGITS)
    f = lm.forcing_full.subs(subs_par).subs(at).subs(t, tv).evalf(DIGITS)
    z = M.LUsolve(f)
    return [float(z[n + i]) for i in range(n)]


def port(s, seed):
    params = {sm.Symbol(k): sm.Float(v, DIGITS) for k, v in s["params"].items()}
    lm = me.LagrangesMethod(s["L"], s["q"], forcelist=s["forces"] or None, frame=s["frame"],
                            hol_coneqs=s["hol"] or None, nonhol_coneqs=s["nonhol"] or None)
    lm.form_lagranges_equations()
    rng = random.Random(seed)
    states = []
    for _ in range(STATES):
        q, qd, tv = project(s, params, rng)
        states.append(dict(
            t=float(tv),
            q=[float(x) for x in q],
            qd=[float(x) for x in qd],
            qdd=accelerations(lm, s, q, qd, tv, params),
        ))
    qs = s["q"]
    forces = generalized_forces(s)
    return dict(
        name=s["name"],
        source="sympy/physics/mechanics/" + s["source"],
        lagrangian=text(sm.expand(s["L"]), qs),
        coordinates=[q.func.__name__ for q in qs],
        constraints=[text(h, qs) for h in s["hol"]] + [text(c, qs) for c in s["nonhol"]],
        forces=None if forces is None else "; ".join(text(f, qs) for f in forces),
        params=s["params"],
        states=states,
    )


def main():
    os.makedirs(OUT, exist_ok=True)
    only = set(sys.argv[1:])
    for seed, s in enumerate(all_systems()):
        if only and s["name"] not in only:
            continue
        data = port(s, 1000 + seed)
        with open(os.path.join(OUT, s["name"] + ".json"), "w") as fh:
            json.dump(data, fh, indent=1)
            fh.write("\n")
        print(s["name"], "ok")


if __name__ == "__main__":
    main()
