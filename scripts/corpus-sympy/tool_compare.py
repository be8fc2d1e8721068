"""Run lagrange's `check` on every line of ../answers.txt and list where its verdict differs
from our label.  Usage: python3 tool_compare.py BINARY PROBLEMS_DIR [OUT]
The labels are never changed by this: it only reports."""
import json
import os
import subprocess
import sys
from collections import Counter

HERE = os.path.dirname(os.path.abspath(__file__))
binary, pdir = sys.argv[1], sys.argv[2]
out = open(sys.argv[3], 'w', encoding='utf-8') if len(sys.argv) > 3 else sys.stdout
n = 0
diff = Counter()
codes_missing = 0
for lineno, line in enumerate(open(os.path.join(HERE, '..', '..', 'tests', 'corpus', 'curvilinear.txt'), encoding='utf-8'), 1):
    if not line.strip() or line.startswith('#'):
        continue
    pid, part, expect, codes, ans = [f.strip() for f in line.rstrip('\n').split(' | ', 4)]
    p = subprocess.run([binary, '--color', 'never', '--problems', pdir, 'check', pid, part, ans, '--json'],
                       capture_output=True, text=True)
    n += 1
    try:
        j = json.loads(p.stdout)
        status = j['status']
        got_codes = [d['code'] for d in j.get('diagnoses', [])]
        reading = j.get('reading', {}).get('plain', '')
        msg = '; '.join('[%s] %s' % (d['code'], d['message']) for d in j.get('diagnoses', []))
    except Exception:
        status = 'error(rc=%d)' % p.returncode
        got_codes = []
        reading = ''
        msg = (p.stderr or p.stdout).strip().replace('\n', ' ')
    if status != expect:
        diff[(expect, status)] += 1
        print('line %d: label %s, tool %s :: %s | %s | %s\n    read as: %s\n    %s' % (
            lineno, expect, status, pid, part, ans, reading, msg[:600]), file=out)
    elif codes != '-' and status != 'correct':
        want = [c for c in codes.replace('+', ',').split(',') if c]
        if not any(any(w2 in got_codes for w2 in w.split('/')) for w in want):
            codes_missing += 1
            print('line %d: verdict agrees (%s) but code %s not among %s :: %s | %s | %s' % (
                lineno, status, codes, got_codes, pid, part, ans), file=out)
print('%d lines checked; disagreements: %s; code mismatches: %d' % (n, dict(diff), codes_missing), file=out)
