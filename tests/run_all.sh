#!/usr/bin/env bash
# Runs every test of beam-impact on a fresh machine (Rust toolchain, gcc, Python 3.11):
# formatting and lints, the Rust tests (physics, paper tables, CLI, FMI importer, MCAP),
# then, in a venv it creates itself (.venv, with the pinned ziglang and cargo-zigbuild on PATH),
# installs the Python package (its native module, the Rust log reader, built by maturin), packs the
# FMUs with the library built for glibc 2.17 and runs the Python tests (fmpy, mcap).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy (beam-impact and the Python package's native module, python/native)"
cargo clippy --release --workspace --all-targets -- -D warnings
echo "== cargo doc"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --quiet
echo "== cargo test --release"
cargo test --release

echo "== Python venv (.venv) with fmpy, mcap, ziglang, cargo-zigbuild and beam_impact (maturin builds its native module)"
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r tests/python/requirements.txt ./python
# cargo-zigbuild finds zig through the venv's python (python3 -m ziglang).
export PATH="$PWD/.venv/bin:$PATH"

echo "== pack the FMUs (the library built for glibc 2.17 by cargo-zigbuild)"
cargo build --release
bin="${CARGO_TARGET_DIR:-target}/release/beam-impact"
"$bin" pack --out target/fmu

echo "== pytest"
BEAM_IMPACT_FMU_DIR="$PWD/target/fmu" BEAM_IMPACT_BIN="$(cd "$(dirname "$bin")" && pwd)/beam-impact" \
  BEAM_IMPACT_REQUIRE_GLIBC_2_17=1 .venv/bin/python -m pytest -q tests/python
echo "== all tests passed"
