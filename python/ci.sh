#!/usr/bin/env bash
# The Python package's CI: a fresh virtual environment in a temporary
# folder, the package built from this checkout (maturin, through pip) with
# the extras the tests, the README's snippet and examples/python/ need, then
# the pytest suite (python/tests). Run by .ci/run after `cargo test --release`,
# whose target/release/cufem the tests compare against.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
venv="$(mktemp -d "${TMPDIR:-/tmp}/cufem-ci-venv.XXXXXX")"
trap 'rm -rf "$venv"' EXIT
start=$(date +%s)
python3 -m venv "$venv"
# the package with its test extra (pytest, tomli_w, vtk and the `all` extra's
# meshio, dask[distributed], matplotlib: the examples and docs snippets run)
"$venv/bin/pip" install -q --disable-pip-version-check "$here[test]"
echo "python/ci.sh: venv and package ready after $(( $(date +%s) - start )) s"
cd "$here/tests"
"$venv/bin/python" -m pytest -q -p no:cacheprovider "$@"
echo "python/ci.sh: done in $(( $(date +%s) - start )) s"
