#!/usr/bin/env bash
# The browser test of report.html (issue 51): runs a shipped example with
# the release binary, then opens its report.html from file:// in headless
# Chromium (Debian's /usr/bin/chromium, driven by playwright-core pinned in
# package-lock.json) and checks what it drew (test.mjs). Installs chromium
# (apt) and the node module (npm ci) only if missing. Leaves the screenshot
# in target/browser/report.png.
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
out=target/browser/run
rm -rf "$out"
target/release/cufem run --quiet --threads 1 --out "$out" "$example" > target/browser/run.log
node tests/browser/test.mjs "$out" target/browser/report.png
