"""Decide whether an answer is correct, incorrect or invalid, by SymPy, from physics.py and
truth.py.  Used by check_labels.py (answers.txt) and check_problems.py (the TOML files).
"""
import glob
import os
import random
import tomllib

import sympy as sp

from physics import SYSTEMS, t
from truth import EQUILIBRIA, FREQS, STEADY, ANY
import lparse
from lparse import ParseError

HERE = os.path.dirname(os.path.abspath(__file__))
PROBLEMS = {}
for f in glob.glob(os.path.join(HERE, '..', '..', 'tests', 'corpus', 'problems', '*.toml')):
    with open(f, 'rb') as fh:
        d = tomllib.load(fh)
    PROBLEMS[d['id']] = d


class Verdict(Exception):
    pass


# ------------------------------------------------------------------------------------
# dimensions: every symbol is scaled by its unit (sM, sL, sT); an expression is homogeneous
# when its scaled value is its value times a monomial in the units.
sM, sL, sT = sp.symbols('sM sL sT', positive=True)


def _dimexpr(txt):
    txt = (txt or '1').strip()
    if txt in ('1', 'rad', 'angle'):
        return sp.S(1)
    out = sp.S(1)
    for tok in txt.split():
        base, _, ex = tok.partition('^')
        e = sp.Rational(ex) if ex else 1
        out *= {'M': sM, 'L': sL, 'T': sT}[base] ** e
    return out


def scale_map(pid):
    s = SYSTEMS[pid]
    d = PROBLEMS[pid]
    sub = {t: t * sT}
    # lengths used only in additive constants of V in physics.py (string lengths)
    for nm in ('la', 'lb', 'ell'):
        sub[sp.Symbol(nm, real=True, positive=True)] = sp.Symbol(nm, real=True, positive=True) * sL
    for name, spec in d['parameters'].items():
        if name in s.params:
            sub[s.params[name]] = s.params[name] * _dimexpr(spec.get('dimension'))
    for c, spec in zip(s.coords, d['coordinates']):
        dim = _dimexpr(spec.get('dimension', '1' if spec.get('periodic') else 'L'))
        sub[c.q] = c.q * dim
        sub[c.qd] = c.qd * dim / sT
        sub[c.qdd] = c.qdd * dim / sT**2
    return sub


def dimension_of(pid, e):
    """The unit monomial of e, or None when e is not homogeneous."""
    e = sp.sympify(e)
    if e == 0:
        return 'zero'
    r = sp.simplify(sp.powsimp(e.xreplace(scale_map(pid)) / e, force=True))
    if r.free_symbols - {sM, sL, sT}:
        return None
    return r


def part_of(pid, partid):
    for p in PROBLEMS[pid]['parts']:
        if p['id'] == partid:
            return p
    raise KeyError((pid, partid))


# ------------------------------------------------------------------------------------
# sampling helpers (used only to decide the sign of factors, never to decide equality)

def param_samples(s, n=400, seed=1):
    rnd = random.Random(seed)
    out = []
    names = list(s.params)
    tries = 0
    while len(out) < n and tries < 100000:
        tries += 1
        vals = {}
        for nm in names:
            lo, hi = 0.01, 100.0
            if nm == 'alpha':
                lo, hi = 0.001, 1.5697
            vals[s.params[nm]] = 10 ** rnd.uniform(-2, 2) if nm != 'alpha' else rnd.uniform(lo, hi)
        ok = all(bool(a.subs(vals)) for a in s.assume)
        if ok:
            out.append(vals)
    return out


def coord_samples(s, n=400, seed=2):
    rnd = random.Random(seed)
    out = []
    special = [0.0, 1.5707963267948966, 3.141592653589793, -1.5707963267948966]
    for i in range(n):
        v = {}
        for c in s.coords:
            if c.domain == 'positive':
                x = 10 ** rnd.uniform(-3, 2)
            elif c.periodic:
                x = rnd.choice(special) if rnd.random() < 0.3 else rnd.uniform(-3.2, 3.2)
            else:
                x = 0.0 if rnd.random() < 0.2 else rnd.uniform(-30, 30)
            v[c.q] = x
            v[c.qd] = 0.0 if rnd.random() < 0.3 else rnd.uniform(-5, 5)
        v[t] = rnd.uniform(-10, 10)
        out.append(v)
    return out


def may_vanish(s, f):
    """True if the expression f (of coordinates, velocities, parameters, t) has a zero (a sign
    change, or an exact zero at a sampled point) in the problem's domain."""
    f = sp.simplify(f)
    if f.is_number:
        return f == 0
    syms = sorted(f.free_symbols, key=str)
    fn = sp.lambdify(syms, f, 'mpmath')
    ps = param_samples(s)
    cs = coord_samples(s)
    signs = set()
    import mpmath
    mpmath.mp.dps = 30
    for i in range(400):
        env = dict(ps[i % len(ps)])
        env.update(cs[i])
        try:
            val = fn(*[env.get(x, 1.0) for x in syms])
        except (ZeroDivisionError, ValueError):
            continue
        val = complex(val)
        if abs(val.imag) > 1e-12 * (1 + abs(val.real)):
            continue
        if val.real == 0 or abs(val.real) < 1e-25:
            return True
        signs.add(val.real > 0)
    return len(signs) > 1


def zero_points_of_massmatrix(s):
    """Points (dicts coordinate -> value) in the domain where det M = 0 (only for angles)."""
    pts = []
    dm = s.detM
    for c in s.coords:
        if c.periodic and dm.has(c.q):
            for v in (sp.S(0), sp.pi):
                if sp.simplify(dm.subs(c.q, v)) == 0:
                    pts.append((c, v))
    return pts


def direction_check(s, A, rows_required=None):
    """Where M is singular (an angle at 0 or pi), the answer's acceleration matrix A must still
    determine every direction that M determines.  Rows of A with a pole there are rescaled to
    their leading order (a pole is not a zero)."""
    for c, v in zero_points_of_massmatrix(s):
        eps = sp.Symbol('eps', positive=True)
        rowsA = []
        for i in range(A.rows):
            row = [sp.simplify(A[i, j].subs(c.q, v + eps)) for j in range(A.cols)]
            # order of the pole
            k = 0
            while any(sp.limit(x * eps**k, eps, 0) in (sp.oo, -sp.oo, sp.zoo) for x in row) and k < 6:
                k += 1
            rowsA.append([sp.limit(x * eps**k, eps, 0) for x in row])
        A0 = sp.Matrix(rowsA)
        M0 = s.M.subs(c.q, v)
        # every row of M0 must lie in the row space of A0
        if sp.Matrix.vstack(A0, M0).rank() != A0.rank():
            return False
    return True


def coeff_matrix(s, Es):
    A = sp.Matrix(len(Es), len(s.qdd), lambda i, j: sp.diff(Es[i], s.qdd[j]))
    for i in range(len(Es)):
        for j in range(len(s.qdd)):
            if any(sp.diff(A[i, j], q) != 0 for q in s.qdd):
                raise Verdict('not linear in the accelerations (not handled)')
    return A


def nonvanishing_combination(s, C):
    """det C (C = A M^-1) must not vanish where M is nonsingular: every factor of its numerator
    must be free of zeros in the domain, or be a factor of det M (a shared singularity)."""
    d = sp.factor(sp.simplify(C.det()))
    num, den = sp.fraction(sp.together(d))
    num = sp.factor(num)
    dmn = sp.factor(sp.fraction(sp.together(s.detM))[0])
    shared = [f for f, _ in sp.factor_list(dmn)[1]]
    const, facs = sp.factor_list(num)
    if const == 0:
        return False
    for f, mult in facs:
        if not (f.free_symbols - set(s.params.values())) and f.is_number:
            continue
        if any(sp.simplify(f - g) == 0 or sp.simplify(f + g) == 0 for g in shared):
            continue
        if may_vanish(s, f):
            return False
    return True


# ------------------------------------------------------------------------------------

QUANTITY_NAMES = {
    'kinetic': {'T'}, 'potential': {'V', 'U'}, 'lagrangian': {'L'}, 'energy-function': {'h'},
}
ALL_QUANTITY_NAMES = {'T', 'V', 'U', 'L', 'h', 'H', 'E', 'p'}


def quantity_of(part):
    q = part.get('quantity')
    if q:
        return q
    pid = part['id']
    if pid in ('kinetic', 'potential', 'lagrangian', 'momentum', 'energy-function'):
        return pid
    if part['kind'] == 'lagrangian':
        return 'lagrangian'
    return None


def strip_name(stmt, part, s, qty):
    """For an expression part: returns the value, or raises Verdict('incorrect'/'invalid')."""
    if stmt[0] == 'expr':
        return stmt[1]
    _, lhs, rhs, lname = stmt
    if lname is None:
        raise Verdict('invalid')  # an equation where an expression is asked
    name, order = lname
    coordname = part.get('coordinate', s.coords[0].name)
    ok = set()
    if qty in QUANTITY_NAMES:
        ok = QUANTITY_NAMES[qty]
    elif qty == 'momentum':
        ok = {'p', 'p' + coordname, 'p_' + coordname}
    elif qty == 'acceleration':
        if order == 2 and name == coordname:
            return rhs
    if order == 0 and name in ok:
        return rhs
    if order == 0 and (name in ALL_QUANTITY_NAMES or name.startswith('p_')):
        raise Verdict('incorrect')  # wrong-name
    raise Verdict('invalid')


def truth_expression(s, part, qty):
    c = part.get('coordinate', s.coords[0].name)
    if qty == 'kinetic':
        return s.T
    if qty == 'potential':
        return s.V
    if qty == 'lagrangian':
        return s.L
    if qty == 'energy-function':
        return s.h
    if qty == 'momentum':
        return s.momenta[c]
    if qty == 'acceleration':
        return s.acc[s.sym(c + '_dd') if False else [cc.qdd for cc in s.coords if cc.name == c][0]]
    raise ValueError(qty)


def equal_expr(s, a, b, up_to_constant):
    d = sp.simplify(sp.expand(a - b))
    if d == 0:
        return True
    if up_to_constant:
        vars_ = list(s.q) + list(s.qd) + [t] + list(s.qdd)
        if all(sp.simplify(sp.diff(d, v)) == 0 for v in vars_):
            return True
        return False
    # final attempt: trig simplification
    return sp.simplify(sp.trigsimp(sp.expand_trig(d))) == 0


def is_total_derivative(s, d):
    if any(sp.diff(d, a) != 0 for a in s.qdd):
        return False
    if any(sp.simplify(sp.diff(d, u, 2)) != 0 for u in s.qd):
        return False
    for q, u in zip(s.q, s.qd):
        # d/dt along the motion: chain rule through q(t), q'(t)
        el = sum(sp.diff(sp.diff(d, u), qq) * uu for qq, uu in zip(s.q, s.qd)) \
            + sum(sp.diff(sp.diff(d, u), uu) * aa for uu, aa in zip(s.qd, s.qdd)) \
            + sp.diff(sp.diff(d, u), t)
        if sp.simplify(el - sp.diff(d, q)) != 0:
            return False
    return True


def judge(pid, partid, answer):
    """Returns 'correct', 'incorrect' or 'invalid'."""
    try:
        return _judge(pid, partid, answer)
    except Verdict as v:
        return str(v)
    except ParseError:
        return 'invalid'


def _judge(pid, partid, answer):
    s = SYSTEMS[pid]
    part = part_of(pid, partid)
    kind = part['kind']
    ctx = lparse.Context(s)
    if answer.strip() == '':
        raise Verdict('invalid')

    if kind in ('expression', 'lagrangian'):
        its = lparse.items(answer)
        if len(its) != 1:
            raise Verdict('invalid')
        qty = quantity_of(part)
        val = strip_name(lparse.statement(its[0], ctx), part, s, qty)
        truth = truth_expression(s, part, qty)
        dv, dt_ = dimension_of(pid, val), dimension_of(pid, truth)
        if dv is None or (dv != 'zero' and dv != dt_):
            return 'incorrect'  # unlike dimensions are never correct
        # L and h are defined up to an added constant whatever the part says (h = sum q' dL/dq' - L)
        upc = part.get('up_to') == 'constant' or qty in ('lagrangian', 'energy-function')
        if equal_expr(s, val, truth, upc):
            return 'correct'
        # A Lagrangian is also defined up to a total time derivative dF(q, t)/dt: the
        # difference D is one exactly when it is linear in the velocities and its
        # Euler-Lagrange expressions vanish identically.
        if qty == 'lagrangian' and is_total_derivative(s, sp.expand(val - truth)):
            return 'correct'
        return 'incorrect'

    if kind == 'steady-motion':
        its = lparse.items(answer)
        if len(its) != 1:
            raise Verdict('invalid')
        st = lparse.statement(its[0], ctx)
        if st[0] != 'expr':
            raise Verdict('invalid')
        truth = STEADY[(pid, partid)]
        if dimension_of(pid, st[1]) != dimension_of(pid, truth):
            return 'incorrect'
        return 'correct' if sp.simplify(st[1] - truth) == 0 else 'incorrect'

    if kind in ('equation', 'equations'):
        its = lparse.items(answer, ';')
        Es = []
        for tk in its:
            st = lparse.statement(tk, ctx)
            if st[0] != 'eq' or st[1] is None:
                raise Verdict('invalid')
            Es.append(sp.expand(st[1] - st[2]))
            if dimension_of(pid, st[1] - st[2]) is None:
                return 'incorrect'  # unlike terms added
        n = len(s.coords)
        if kind == 'equation' and len(Es) != 1:
            raise Verdict('invalid')
        if kind == 'equations' and len(Es) != n:
            return 'incorrect'  # equation-count
        # each holds on the true motion
        for E in Es:
            if not any(E.has(a) for a in s.qdd):
                return 'incorrect'
            if sp.simplify(s.onshell(E)) != 0:
                if sp.simplify(sp.trigsimp(sp.expand_trig(s.onshell(E)))) != 0:
                    return 'incorrect'
        A = coeff_matrix(s, Es)
        C = sp.simplify(A * s.M.inv())
        # consistency: E = C * EL exactly
        EL = sp.Matrix(s.EL)
        for i, E in enumerate(Es):
            assert sp.simplify(E - (C[i, :] * EL)[0]) == 0
        if kind == 'equation':
            cname = part.get('coordinate', s.coords[0].name)
            k = [c.name for c in s.coords].index(cname)
            for j in range(n):
                if j != k and sp.simplify(C[0, j]) != 0:
                    return 'incorrect'  # not (only) this coordinate's equation
            lam = sp.Matrix([[C[0, k]]])
            if not nonvanishing_lambda(s, lam[0, 0]):
                return 'incorrect'
            # direction-wise: where M still determines q_k'', the answer must too
            Afull = sp.zeros(n, n)
            Mk = s.M
            for c, v in zero_points_of_massmatrix(s):
                if any(Mk[k, j].subs(c.q, v) != 0 for j in range(n)):
                    if not direction_check_row(s, A[0, :], k, c, v):
                        return 'incorrect'
            return 'correct'
        if not nonvanishing_combination(s, C):
            return 'incorrect'
        if not direction_check(s, A):
            return 'incorrect'
        return 'correct'

    if kind == 'equilibria':
        return judge_equilibria(s, pid, part, answer, ctx)

    if kind == 'frequencies':
        return judge_frequencies(s, pid, part, answer, ctx)

    raise ValueError(kind)


def nonvanishing_lambda(s, lam):
    num, den = sp.fraction(sp.together(sp.simplify(lam)))
    const, facs = sp.factor_list(sp.factor(num))
    if const == 0:
        return False
    dmn = sp.factor(sp.fraction(sp.together(s.detM))[0])
    shared = [f for f, _ in sp.factor_list(dmn)[1]]
    for f, mult in facs:
        if f.is_number:
            continue
        if any(sp.simplify(f - g) == 0 or sp.simplify(f + g) == 0 for g in shared):
            continue
        if may_vanish(s, f):
            return False
    return True


def direction_check_row(s, Arow, k, c, v):
    eps = sp.Symbol('eps', positive=True)
    row = [sp.simplify(x.subs(c.q, v + eps)) for x in Arow]
    kk = 0
    while any(sp.limit(x * eps**kk, eps, 0) in (sp.oo, -sp.oo, sp.zoo) for x in row) and kk < 6:
        kk += 1
    row0 = [sp.limit(x * eps**kk, eps, 0) for x in row]
    return any(x != 0 for x in row0)


# ------------------------------------------------------------------------------------
STAB = ('stable', 'unstable', 'marginal')


def split_stability(tk):
    """Strip a trailing `stable`, `(stable)` from an item's tokens."""
    if len(tk) >= 3 and tk[-1].kind == 'op' and tk[-1].val == ')' and tk[-2].kind == 'name' and tk[-2].val in STAB \
            and tk[-3].kind == 'op' and tk[-3].val == '(':
        return tk[:-3], tk[-2].val
    if tk and tk[-1].kind == 'name' and tk[-1].val in STAB:
        return tk[:-1], tk[-1].val
    return tk, None


def parse_value(tk, ctx):
    if len(tk) == 1 and tk[0].kind == 'name' and tk[0].val == 'any':
        return ANY
    v = lparse.parse_toks(tk, ctx)
    if any(v.has(x) for x in ctx.sys.q + ctx.sys.qd + ctx.sys.qdd + [t]):
        raise Verdict('invalid')
    return v


def judge_equilibria(s, pid, part, answer, ctx):
    names = [c.name for c in s.coords]
    txt = answer.strip()
    truth = EQUILIBRIA[pid]
    if txt.lower() == 'none':
        return 'correct' if not truth else 'incorrect'
    toks = lparse.tokenize(txt)
    groups = lparse.split_top(toks, ',;')
    points = []  # list of (dict, stability)
    cur, cur_stab = {}, None
    for tk, sep in groups:
        tk, stab = split_stability(tk)
        if not tk:
            raise Verdict('invalid')
        if tk[0].kind == 'op' and tk[0].val == '(' and tk[-1].kind == 'op' and tk[-1].val == ')' and \
                len(lparse.split_top(tk[1:-1], ',')) > 1:
            if cur:
                points.append((cur, cur_stab))
                cur, cur_stab = {}, None
            comps = [x for x, _ in lparse.split_top(tk[1:-1], ',')]
            if len(comps) != len(names):
                raise Verdict('invalid')
            points.append(({names[i]: parse_value(comps[i], ctx) for i in range(len(names))}, stab))
            continue
        parts = lparse.split_top(tk, '=')
        if len(parts) == 2:
            lt = parts[0][0]
            if len(lt) != 1 or lt[0].kind != 'name' or lt[0].val not in names or lt[0].order:
                raise Verdict('invalid')
            nm = lt[0].val
            val = parse_value(parts[1][0], ctx)
            if nm in cur:
                points.append((cur, cur_stab))
                cur, cur_stab = {}, None
            cur[nm] = val
            if stab:
                cur_stab = stab
            if sep == ';':
                points.append((cur, cur_stab))
                cur, cur_stab = {}, None
        elif len(parts) == 1:
            if len(names) != 1:
                raise Verdict('invalid')
            if cur:
                points.append((cur, cur_stab))
                cur, cur_stab = {}, None
            points.append(({names[0]: parse_value(tk, ctx)}, stab))
        else:
            raise Verdict('invalid')
    if cur:
        points.append((cur, cur_stab))
    for p, _ in points:
        if set(p) != set(names):
            return 'incorrect'
    # match answer points to true points one to one
    used = set()
    for p, stab in points:
        hit = None
        for i, (tp, tstab) in enumerate(truth):
            if i in used:
                continue
            if all(same_coord(s, nm, p[nm], tp[nm]) for nm in names):
                hit = i
                break
        if hit is None:
            return 'incorrect'
        used.add(hit)
        if stab is not None and stab != truth[hit][1]:
            return 'incorrect'
    if len(used) != len(truth):
        return 'incorrect'
    return 'correct'


def same_coord(s, nm, a, b):
    if a is ANY or b is ANY:
        return a is b
    c = [cc for cc in s.coords if cc.name == nm][0]
    d = sp.simplify(a - b)
    if d == 0:
        return True
    if c.periodic:
        k = sp.simplify(d / (2 * sp.pi))
        return k.is_integer is True
    return False


def judge_frequencies(s, pid, part, answer, ctx):
    truth = list(FREQS[(pid, part['id'])])
    its = lparse.items(answer)
    vals = []
    for tk in its:
        st = lparse.statement(tk, ctx)
        if st[0] == 'expr':
            v = st[1]
        else:
            _, lhs, rhs, lname = st
            if lname is None:
                raise Verdict('invalid')
            nm = lname[0]
            okn = nm.rstrip('0123456789') in ('omega', 'w', 'omega_') and not (nm in ctx.params)
            if not okn:
                raise Verdict('invalid')
            v = rhs
        if any(v.has(x) for x in s.q + s.qd + s.qdd + [t]):
            raise Verdict('invalid')
        if v != 0 and dimension_of(pid, v) != (1 / sT**(2 if part.get('squared') else 1)):
            return 'incorrect'
        vals.append(v)
    used = set()
    for v in vals:
        hit = None
        for i, tv in enumerate(truth):
            if i not in used and sp.simplify(sp.radsimp(v - tv)) == 0:
                hit = i
                break
            if i not in used and sp.simplify(sp.expand(v**2 - tv**2)) == 0 and \
                    sp.simplify(v - tv) != 0:
                # possibly equal: check sign numerically at a sample (both nonnegative?)
                ps = param_samples(s, 5)
                if all(abs(complex((v - tv).subs(p).evalf(30))) < 1e-20 for p in ps):
                    hit = i
                    break
        if hit is None:
            return 'incorrect'
        used.add(hit)
    return 'correct' if len(used) == len(truth) else 'incorrect'
