#!/usr/bin/env bash
# Runs every test of beam-impact on a fresh machine (Rust toolchain, gcc, Python 3.11):
# formatting and lints, the Rust tests (physics, paper tables, CLI, FMI importer, MCAP),
# then packs the FMUs and runs the Python tests (fmpy, mcap) in a venv it creates itself.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --release --all-targets -- -D warnings
echo "== cargo doc"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet
echo "== cargo test --release"
cargo test --release
echo "== pack the FMUs"
cargo build --release
bin="${CARGO_TARGET_DIR:-target}/release/beam-impact"
"$bin" pack --out target/fmu

echo "== Python venv (.venv) with fmpy and mcap"
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r tests/python/requirements.txt
echo "== pytest"
BEAM_IMPACT_FMU_DIR="$PWD/target/fmu" BEAM_IMPACT_BIN="$(cd "$(dirname "$bin")" && pwd)/beam-impact" \
  .venv/bin/python -m pytest -q tests/python
echo "== all tests passed"
