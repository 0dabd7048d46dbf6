#!/usr/bin/env bash
# Wall time of every paper example: median of N runs (default 3), release
# build, with increments, Newton iterations, numeric factorizations, solves
# that reused an earlier factorization (PCG), PCG iterations, the reuse ratio
# (reused / all solves) and the phase split of the last run; then the peak
# memory. "f32": factorizations stored in single precision
# (solver.factor_precision). Usage: bench/examples.sh [N] [CUFEM_BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-3}
bin=${2:-./target/release/cufem}
[ "$bin" = ./target/release/cufem ] && cargo build --release --quiet
printf "%-24s %7s %9s %5s %5s %5s %5s %6s %6s %6s %8s %8s %8s %8s\n" example DOF "median s" incr iters facts f32 reused krylov reuse% assembly factor solve "peak MiB"
for ex in block_indentation bending_compact_4L9 bending_compact_16L9 bending_tube_20L9 bending_tube_28L9 cantilevers_contact; do
  times=()
  for _ in $(seq "$n"); do
    "$bin" run "examples/$ex.toml" --out "out/bench_$ex" --quiet > /dev/null
    times+=("$(python3 -c "import json;print(json.load(open('out/bench_$ex/summary.json'))['wall_time_s'])")")
  done
  python3 - "$ex" "out/bench_$ex/summary.json" "${times[@]}" <<'PY'
import json, statistics, sys
ex, path, *t = sys.argv[1:]
s = json.load(open(path)); tm = s["timings"]
facts, reused = tm.get("factorizations", s["newton_iterations"]), tm.get("reused_factorizations", 0)
print(f"{ex:<24} {s['dof']:>7} {statistics.median(map(float, t)):>9.2f} {s['increments']:>5} {s['newton_iterations']:>5} "
      f"{facts:>5} {tm.get('single_factorizations', 0):>5} {reused:>6} {tm.get('krylov_iterations', 0):>6} {100 * reused / max(facts + reused, 1):>6.0f} "
      f"{tm['assembly_s'] + tm['contact_s']:>8.2f} {tm['factorization_s']:>8.2f} {tm['solve_s']:>8.2f} "
      f"{s['memory']['peak_bytes'] / 2**20:>8.0f}")
PY
done
