#!/bin/bash
# usage: bench/run_examples.sh BIN OUTDIR — every shipped example run by BIN (one thread) into
# OUTDIR/NAME, exit codes in OUTDIR/rc.txt; with bench/compare_runs.py, the check that a refactoring
# changes no result (run it on the old and the new binary, then compare the two folders).
BIN=$(realpath "$1"); OUT=$(realpath -m "$2"); mkdir -p "$OUT"
cd "$(dirname "$0")/.."
for f in examples/*.toml examples/sections/*.toml; do
  [ -f "$f" ] || continue
  n=$(basename $f .toml)
  $BIN run --quiet --threads 1 --out $OUT/$n --force $f > $OUT/$n.log 2>&1; echo "$n rc=$?" >> $OUT/rc.txt
done
