#!/usr/bin/env bash
# The browser test of report.html (issue 51): runs a shipped example with
# the release binary, then opens its report.html from file:// in headless
# Chromium (Debian's /usr/bin/chromium, driven by playwright-core pinned in
# package-lock.json) and checks what it drew (test.mjs); then the pages of
# the features a history example lacks: a buckling run's mode shapes
# (examples/column_buckling.toml) and the ply damage of the notched strip
# (examples/notched_strip_coarse.toml pulled to a third of its stretch in 20
# increments: damage begins, in 0.05 s), and the verify page of examples/cantilever_timoshenko.toml at refine 1 (0.5
# s): its CalculiX overlays and whole-field table; the page of an adaptive
# run (the same cantilever, --adapt 0.05: 2 cycles in 0.3 s). Installs chromium (apt) and the
# node module (npm ci) and CalculiX (apt, calculix-ccx) only if missing. Leaves the screenshots in
# target/browser/<run>.png.
# Usage: bash tests/browser/run_browser_test.sh [EXAMPLE.toml]
set -euo pipefail
cd "$(dirname "$0")/../.."
example=${1:-examples/block_indentation_unload.toml}
if [ ! -x /usr/bin/chromium ]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium > /dev/null
fi
if [ ! -d tests/browser/node_modules/playwright-core ]; then
  (cd tests/browser && npm ci --no-audit --no-fund --silent)
fi
cargo build --release --quiet --bin cufem
mkdir -p target/browser
run() { # run MODEL.toml FOLDER
  rm -rf "target/browser/$2"
  target/release/cufem run --quiet --threads 1 --out "target/browser/$2" "$1" >> target/browser/run.log
}
: > target/browser/run.log
run "$example" run
run examples/column_buckling.toml buckling
run examples/bending_compact_4L9.toml bending
strip=target/browser/strip.toml
sed 's/displacement = { x = 1.5e-4 }/displacement = { x = 5e-5 }/; s/^increments = 150$/increments = 20/' \
  examples/notched_strip_coarse.toml > "$strip"
grep -q 'x = 5e-5' "$strip" && grep -q '^increments = 20$' "$strip" || { echo "notched strip: edit failed"; exit 1; }
run "$strip" strip
if ! command -v ccx > /dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq calculix-ccx > /dev/null
fi
rm -rf target/browser/adapt
target/release/cufem run --quiet --threads 1 --adapt 0.05 --max-dof 6000 --out target/browser/adapt \
  examples/cantilever_timoshenko.toml >> target/browser/run.log
rm -rf target/browser/verify
target/release/cufem verify --quiet --threads 1 --refine 1 --out target/browser/verify \
  examples/cantilever_timoshenko.toml >> target/browser/run.log
node tests/browser/test.mjs target/browser target/browser/{run,buckling,bending,strip,adapt,verify}
