#!/bin/sh
# Prove every label and every reference answer with SymPy, then (optionally) compare the tool.
# Usage: sh run_all.sh [LAGRANGE_BINARY]
set -e
cd "$(dirname "$0")"
python3 check_problems.py
python3 check_labels.py
if [ -n "$1" ]; then
  "$1" --problems ../../tests/corpus/problems problems verify
  python3 tool_compare.py "$1" ../../tests/corpus/problems
fi
