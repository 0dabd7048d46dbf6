#!/usr/bin/env bash
# Wall time of every paper example: median of N runs (default 3), release
# build, with increments, Newton iterations and the phase split of the last
# run. Usage: bench/examples.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-3}
cargo build --release --quiet
printf "%-24s %8s %10s %6s %6s %9s %9s %9s %9s\n" example DOF "median s" incr iters assembly contact factor solve
for ex in block_indentation bending_compact_4L9 bending_compact_16L9 bending_tube_20L9 bending_tube_28L9 cantilevers_contact; do
  times=()
  for _ in $(seq "$n"); do
    ./target/release/cufem run "examples/$ex.toml" --out "out/bench_$ex" --quiet > /dev/null
    times+=("$(python3 -c "import json;print(json.load(open('out/bench_$ex/summary.json'))['wall_time_s'])")")
  done
  python3 - "$ex" "out/bench_$ex/summary.json" "${times[@]}" <<'PY'
import json, statistics, sys
ex, path, *t = sys.argv[1:]
s = json.load(open(path)); tm = s["timings"]
print(f"{ex:<24} {s['dof']:>8} {statistics.median(map(float, t)):>10.2f} {s['increments']:>6} {s['newton_iterations']:>6} "
      f"{tm['assembly_s']:>9.2f} {tm['contact_s']:>9.2f} {tm['factorization_s']:>9.2f} {tm['solve_s']:>9.2f}")
PY
done
