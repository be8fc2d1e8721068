"""Print how lparse reads every answer (for a human to audit the translator)."""
import os, sys
import sympy as sp
import lparse
from physics import SYSTEMS
HERE = os.path.dirname(os.path.abspath(__file__))
for line in open(os.path.join(HERE, '..', '..', 'tests', 'corpus', 'curvilinear.txt'), encoding='utf-8'):
    if not line.strip() or line.startswith('#'):
        continue
    pid, part, expect, codes, ans = [f.strip() for f in line.split(' | ', 4)]
    if len(sys.argv) > 1 and sys.argv[1] == 'fancy' and ans.isascii() and '*' in ans:
        continue
    ctx = lparse.Context(SYSTEMS[pid])
    try:
        its = lparse.items(ans, ';')
        out = []
        for tk in its:
            # split on top-level commas only for display
            for sub, _ in lparse.split_top(tk, ','):
                try:
                    st = lparse.statement(sub, ctx)
                    out.append(' = '.join(str(x) for x in st[1:3]) if st[0] == 'eq' else str(st[1]))
                except lparse.ParseError as e:
                    out.append('<%s>' % e)
        print('%-8s %s\n          %s' % (expect, ans, ' ;; '.join(out)))
    except lparse.ParseError as e:
        print('%-8s %s\n          PARSE ERROR %s' % (expect, ans, e))
