"""A small reader of the answer syntax documented in lagrange's README ("The language"),
written from the documentation alone, producing SymPy objects in the symbols of physics.py.

It is deliberately strict where the README says lagrange refuses an input (`sin θ²`,
`sin θ/2`, an unknown run of letters such as `mgl`, two numbers side by side, `sin^-1`),
so that lines labelled `invalid` can be confirmed: a ParseError means "cannot be read".
"""
import unicodedata
import sympy as sp


class ParseError(Exception):
    pass


GREEK = {
    'θ': 'theta', 'φ': 'phi', 'ϕ': 'phi', 'ω': 'omega', 'Ω': 'Omega', 'α': 'alpha', 'β': 'beta',
    'ρ': 'rho', 'π': 'pi', 'ψ': 'psi', 'λ': 'lambda', 'μ': 'mu', 'γ': 'gamma', 'δ': 'delta',
}
SUB = {chr(0x2080 + i): str(i) for i in range(10)}
SUP = {'⁰': '0', '¹': '1', '²': '2', '³': '3', '⁴': '4', '⁵': '5', '⁶': '6', '⁷': '7', '⁸': '8', '⁹': '9', '⁻': '-'}
FRAC = {'½': sp.Rational(1, 2), '¼': sp.Rational(1, 4), '¾': sp.Rational(3, 4)}
PRIMES = "'’′"
DOT1, DOT2 = '\u0307', '\u0308'

FUNCS = {
    'sin': sp.sin, 'cos': sp.cos, 'tan': sp.tan, 'sec': sp.sec, 'csc': sp.csc, 'cot': sp.cot,
    'asin': sp.asin, 'acos': sp.acos, 'atan': sp.atan, 'arcsin': sp.asin, 'arccos': sp.acos,
    'arctan': sp.atan, 'sinh': sp.sinh, 'cosh': sp.cosh, 'tanh': sp.tanh, 'exp': sp.exp,
    'log': sp.log, 'ln': sp.log, 'sqrt': sp.sqrt, 'abs': sp.Abs,
}


class Tok:
    def __init__(self, kind, val, space, order=0):
        self.kind, self.val, self.space, self.order = kind, val, space, order

    def __repr__(self):
        return 'Tok(%s,%r,%s,%d)' % (self.kind, self.val, self.space, self.order)


def is_letter(ch):
    return ch.isalpha() and ch not in FRAC and ch not in SUP


def tokenize(s):
    s = unicodedata.normalize('NFD', s)
    s = s.replace('−', '-').replace('·', '*').replace('×', '*').replace('**', '^').replace('∓', '±')
    toks = []
    i, n = 0, len(s)
    space = False
    while i < n:
        ch = s[i]
        if ch.isspace():
            space = True
            i += 1
            continue
        if ch in '0123456789' or (ch == '.' and i + 1 < n and s[i + 1] in '0123456789'):
            j = i
            while j < n and (s[j] in '0123456789' or s[j] == '.'):
                j += 1
            if j < n and s[j] in 'eE' and j + 1 < n and (s[j + 1].isdigit() or (s[j + 1] in '+-' and j + 2 < n and s[j + 2].isdigit())):
                k = j + 1
                if s[k] in '+-':
                    k += 1
                while k < n and s[k].isdigit():
                    k += 1
                # a number followed by letters e.g. `2e` is left alone; here it is an exponent
                j = k
            txt = s[i:j]
            if txt.count('.') > 1:
                raise ParseError('bad number ' + txt)
            toks.append(Tok('num', sp.Rational(txt), space))
            i = j
        elif ch in FRAC:
            toks.append(Tok('num', FRAC[ch], space))
            i += 1
        elif ch in SUP:
            j = i
            while j < n and s[j] in SUP:
                j += 1
            txt = ''.join(SUP[c] for c in s[i:j])
            try:
                val = int(txt)
            except ValueError:
                raise ParseError('bad superscript')
            toks.append(Tok('sup', sp.Integer(val), space))
            i = j
        elif is_letter(ch) or ch == '_':
            j = i
            name = ''
            order = 0
            while j < n and (is_letter(s[j]) or s[j] in '0123456789' or s[j] == '_' or s[j] in SUB or s[j] in (DOT1, DOT2)):
                c = s[j]
                if c == DOT1:
                    order += 1
                elif c == DOT2:
                    order += 2
                elif c in SUB:
                    name += SUB[c]
                elif c in GREEK:
                    name += GREEK[c]
                elif unicodedata.combining(c):
                    raise ParseError('unknown mark')
                else:
                    name += c
                j += 1
            while j < n and s[j] in PRIMES + '″':
                order += 2 if s[j] == '″' else 1
                j += 1
            while j < n and s[j] in SUB:
                name += SUB[s[j]]
                j += 1
            toks.append(Tok('name', name, space, order))
            i = j
        elif ch in '+-*/^()[],;=±√':
            toks.append(Tok('op', ch, space))
            i += 1
        else:
            raise ParseError('unexpected character %r' % ch)
        space = False
    return toks


class Context:
    """Names known in a problem: coordinates (with their velocity and acceleration symbols),
    parameters, t and pi."""

    def __init__(self, system, extra_names=()):
        self.sys = system
        self.coords = {c.name: c for c in system.coords}
        self.params = dict(system.params)
        self.extra = set(extra_names)  # words allowed in list answers (any, stable, ...)

    def resolve(self, name, order):
        from physics import t
        base = name
        cands = [base]
        if '_' in base:
            # m_1 -> m1 (an underscore before digits)
            import re
            cands.append(re.sub(r'_(?=\d)', '', base))
        for nm in cands:
            if nm in self.coords:
                c = self.coords[nm]
                return [c.q, c.qd, c.qdd][order] if order <= 2 else self._bad(name)
            if order == 0 and nm in self.params:
                return self.params[nm]
            if order == 0 and nm == 't':
                return t
            if order == 0 and nm == 'pi':
                return sp.pi
        # thetadot, theta_dot, thetaddot
        for suf, o in (('_ddot', 2), ('ddot', 2), ('_dot', 1), ('dot', 1)):
            if base.endswith(suf) and order == 0:
                stem = base[:-len(suf)]
                if stem in self.coords:
                    c = self.coords[stem]
                    return [c.q, c.qd, c.qdd][o]
        raise ParseError('unknown symbol ' + name + "'" * order)

    def _bad(self, name):
        raise ParseError('third derivative of ' + name)


class Parser:
    def __init__(self, toks, ctx):
        self.toks, self.i, self.ctx = toks, 0, ctx

    def peek(self, k=0):
        j = self.i + k
        return self.toks[j] if j < len(self.toks) else None

    def next(self):
        t = self.peek()
        if t is None:
            raise ParseError('unexpected end')
        self.i += 1
        return t

    def at_op(self, ch, k=0):
        t = self.peek(k)
        return t is not None and t.kind == 'op' and t.val == ch

    def expect(self, ch):
        t = self.next()
        if t.kind != 'op' or t.val != ch:
            raise ParseError('expected %s' % ch)

    # expression grammar ---------------------------------------------------------
    def expr(self):
        left = self.term()
        while self.at_op('+') or self.at_op('-'):
            op = self.next().val
            right = self.term()
            left = left + right if op == '+' else left - right
        return left

    def starts_primary(self, t):
        if t is None:
            return False
        if t.kind in ('num', 'name'):
            return True
        return t.kind == 'op' and t.val in '([√'

    def term(self):
        left, last_num = self.unary()
        while True:
            t = self.peek()
            if t is not None and t.kind == 'op' and t.val in '*/':
                self.next()
                right, last_num = self.unary()
                left = left * right if t.val == '*' else left / right
            elif self.starts_primary(t):
                if t.kind == 'num' and last_num:
                    raise ParseError('two numbers side by side')
                right, last_num = self.power()
                left = left * right
            else:
                return left

    def unary(self):
        if self.at_op('-'):
            self.next()
            v, _ = self.unary()
            return -v, False
        if self.at_op('+'):
            self.next()
            return self.unary()
        return self.power()

    def power(self):
        """Returns (value, is_plain_number) for the implicit-multiplication check."""
        base, isnum = self.postfix()
        if self.at_op('^'):
            self.next()
            if self.at_op('-'):
                self.next()
                e, _ = self.power()
                e = -e
            else:
                e, _ = self.power()
            return base ** e, False
        return base, isnum

    def postfix(self):
        v, isnum = self.primary()
        while True:
            t = self.peek()
            if t is not None and t.kind == 'sup':
                self.next()
                v = v ** t.val
                isnum = False
            else:
                break
        return v, isnum

    def group(self):
        t = self.next()
        if t.kind == 'op' and t.val in '([':
            close = ')' if t.val == '(' else ']'
            v = self.expr()
            if self.at_op(','):
                raise ParseError('tuple inside an expression')
            self.expect(close)
            return v
        raise ParseError('expected a bracket')

    def primary(self):
        t = self.peek()
        if t is None:
            raise ParseError('unexpected end')
        if t.kind == 'num':
            self.next()
            return t.val, True
        if t.kind == 'op' and t.val in '([':
            return self.group(), False
        if t.kind == 'op' and t.val == '√':
            self.next()
            v, _ = self.postfix_nosup()
            return sp.sqrt(v), False
        if t.kind == 'name':
            name = t.val
            # d/dt(...)
            if name == 'd' and t.order == 0 and self.at_op('/', 1):
                t2 = self.peek(2)
                if t2 is not None and t2.kind == 'name' and t2.val == 'dt':
                    self.i += 3
                    inner = self.group()
                    return self.ctx.sys.ddt(inner), False
            if name in ('dot', 'ddot') and self.at_op('(', 1):
                self.next()
                self.expect('(')
                a = self.next()
                if a.kind != 'name' or a.val not in self.ctx.coords or a.order:
                    raise ParseError('dot() of a non-coordinate')
                self.expect(')')
                c = self.ctx.coords[a.val]
                return (c.qd if name == 'dot' else c.qdd), False
            if name in FUNCS and t.order == 0:
                return self.function(name), False
            if name.startswith('sqrt') and name[4:].isdigit():
                self.next()
                return sp.sqrt(sp.Integer(name[4:])), False
            self.next()
            return self.ctx.resolve(name, t.order), False
        raise ParseError('unexpected %r' % (t.val,))

    def postfix_nosup(self):
        t = self.peek()
        if t is not None and t.kind == 'num':
            self.next()
            return t.val, True
        if t is not None and t.kind == 'name' and t.val not in FUNCS:
            self.next()
            return self.ctx.resolve(t.val, t.order), False
        return self.primary()

    def function(self, name):
        f = FUNCS[name]
        self.next()
        powr = None
        if self.at_op('^'):
            self.next()
            if self.at_op('-'):
                raise ParseError('sin^-1 is refused')
            e = self.next()
            if e.kind != 'num':
                raise ParseError('function power must be a number')
            powr = e.val
        elif self.peek() is not None and self.peek().kind == 'sup':
            e = self.next()
            if e.val < 0:
                raise ParseError('sin⁻¹ is refused')
            powr = e.val
        if self.at_op('(') or self.at_op('['):
            arg = self.group()
        else:
            # bare argument: an optional number and the name right after it
            parts = []
            t = self.peek()
            if t is not None and t.kind == 'num':
                self.next()
                parts.append(t.val)
                t = self.peek()
            if t is not None and t.kind == 'name' and t.val not in FUNCS:
                self.next()
                parts.append(self.ctx.resolve(t.val, t.order))
            if not parts:
                raise ParseError('function without argument')
            nt = self.peek()
            if nt is not None and (nt.kind == 'sup' or (nt.kind == 'op' and nt.val == '^')):
                raise ParseError('ambiguous: sin θ^2')
            if nt is not None and nt.kind == 'op' and nt.val == '/' and not nt.space:
                raise ParseError('ambiguous: sin θ/2')
            arg = sp.Mul(*parts)
        v = f(arg)
        if powr is not None:
            v = v ** powr
        return v


def parse_expr(s, ctx):
    toks = tokenize(s)
    if not toks:
        raise ParseError('empty')
    p = Parser(toks, ctx)
    v = p.expr()
    if p.peek() is not None:
        raise ParseError('trailing input %r' % (p.peek().val,))
    return v


# ---------------------------------------------------------------------------------------
# statements: splitting on top-level ; , = and reading named quantities

def split_top(toks, seps):
    out, cur, depth = [], [], 0
    for t in toks:
        if t.kind == 'op' and t.val in '([':
            depth += 1
        elif t.kind == 'op' and t.val in ')]':
            depth -= 1
        if depth == 0 and t.kind == 'op' and t.val in seps:
            out.append((cur, t.val))
            cur = []
        else:
            cur.append(t)
    out.append((cur, None))
    return out


def parse_toks(toks, ctx):
    if not toks:
        raise ParseError('empty')
    p = Parser(toks, ctx)
    v = p.expr()
    if p.peek() is not None:
        raise ParseError('trailing input %r' % (p.peek().val,))
    return v


def statement(toks, ctx):
    """('eq', lhs, rhs, lhs_name) or ('expr', e)."""
    parts = split_top(toks, '=')
    if len(parts) == 1:
        return ('expr', parse_toks(toks, ctx))
    if len(parts) > 2:
        raise ParseError('two = signs')
    lt, rt = parts[0][0], parts[1][0]
    lname = None
    if len(lt) == 1 and lt[0].kind == 'name':
        lname = (lt[0].val, lt[0].order)
    rhs = parse_toks(rt, ctx)
    try:
        lhs = parse_toks(lt, ctx)
    except ParseError:
        if lname is None:
            raise
        lhs = None
    return ('eq', lhs, rhs, lname)


def expand_pm(tk):
    """An item with ± stands for two items (README: `±` giving two items)."""
    for i, t in enumerate(tk):
        if t.kind == 'op' and t.val == '±':
            a = tk[:i] + [Tok('op', '+', t.space)] + tk[i + 1:]
            b = tk[:i] + [Tok('op', '-', t.space)] + tk[i + 1:]
            return expand_pm(a) + expand_pm(b)
    return [tk]


def items(s, seps=',;'):
    toks = tokenize(s)
    if not toks:
        raise ParseError('empty')
    out = []
    for tk, _ in split_top(toks, seps):
        out += expand_pm(tk)
    return out
