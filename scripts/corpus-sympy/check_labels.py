"""Read tests/corpus/curvilinear.txt and confirm every label by SymPy (judge.py).  Prints each line whose
label is not confirmed, then a summary; exit status 0 only if every label is confirmed."""
import os
import sys
from collections import Counter
from judge import judge, PROBLEMS, part_of

HERE = os.path.dirname(os.path.abspath(__file__))
path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, '..', '..', 'tests', 'corpus', 'curvilinear.txt')
bad = 0
counts = Counter()
per_problem = Counter()
for lineno, line in enumerate(open(path, encoding='utf-8'), 1):
    line = line.rstrip('\n')
    if not line.strip() or line.lstrip().startswith('#'):
        continue
    fields = line.split(' | ', 4)
    if len(fields) != 5:
        print('MALFORMED line %d: %s' % (lineno, line))
        bad += 1
        continue
    pid, partid, expect, codes, answer = [f.strip() if i < 4 else f for i, f in enumerate(fields)]
    answer = answer.strip()
    if pid not in PROBLEMS:
        print('UNKNOWN PROBLEM line %d: %s' % (lineno, pid))
        bad += 1
        continue
    part_of(pid, partid)
    got = judge(pid, partid, answer)
    counts[expect] += 1
    per_problem[pid] += 1
    if got != expect:
        bad += 1
        print('NOT CONFIRMED line %d: label %s, sympy %s :: %s | %s | %s' % (lineno, expect, got, pid, partid, answer))
print('lines by label:', dict(counts), 'total', sum(counts.values()))
print('lines by problem:', dict(sorted(per_problem.items())))
print('%d line(s) whose label SymPy does not confirm' % bad)
sys.exit(1 if bad else 0)
