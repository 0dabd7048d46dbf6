#!/usr/bin/env bash
# Deliberate breakages of the core modules (cargo-mutants), checked against
# the fast part of the suite: unit tests, convergence, plasticity, contact,
# linear verification and the compact-bar and block examples (the tube and
# cantilever examples and the 10,000-case mutation test add minutes per
# mutant and no coverage of these modules).
#
# Usage: bench/mutants.sh [SHARD]   e.g. bench/mutants.sh 0/8 runs one eighth.
# A full run is ~900 mutants at ~1 min each on two cores; results in mutants.out/.
# Needs: cargo install cargo-mutants
set -euo pipefail
cd "$(dirname "$0")/.."
shard=${1:-0/1}
mkdir -p mutants.out
cargo mutants --shard "$shard" --output "mutants.out/${shard//\//-of-}" \
  -f 'src/elements/**' -f 'src/materials/**' -f 'src/contact/**' -f 'src/assembly/**' -f 'src/solver/**' \
  -- --lib --test convergence --test plasticity --test contact --test linear_verification --test examples \
  -- --skip tube --skip cantilevers
