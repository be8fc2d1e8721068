"""Check every reference answer (must be correct) and every `wrong` example (must not be
correct) of the TOML files against judge.py, i.e. against our own physics."""
import sys
from judge import PROBLEMS, judge

bad = 0
n = 0
for pid, d in sorted(PROBLEMS.items()):
    for part in d['parts']:
        ans = part['answer']
        if isinstance(ans, list):
            if part['kind'] == 'equations':
                ans = '; '.join(ans)
            elif part['kind'] == 'equilibria':
                st = part.get('stability')
                items = []
                for i, a in enumerate(ans):
                    pt = a
                    if ',' in a:  # a point of several coordinates: `r = .., theta = ..`
                        pt = a
                    items.append(pt + (' (%s)' % st[i] if st else ''))
                ans = '; '.join(items)
            else:
                ans = ', '.join(ans)
        v = judge(pid, part['id'], ans)
        n += 1
        if v != 'correct':
            bad += 1
            print('REFERENCE NOT CONFIRMED', pid, part['id'], v, ans)
        for w in part.get('wrong', []):
            n += 1
            v = judge(pid, part['id'], w)
            if v == 'correct':
                bad += 1
                print('WRONG EXAMPLE IS CORRECT', pid, part['id'], w)
print('%d checks, %d problems' % (n, bad))
sys.exit(1 if bad else 0)
