#!/usr/bin/env bash
# Runs every test of beam-impact on a fresh machine (Rust toolchain, gcc, Python 3.11):
# formatting and lints, the Rust tests (physics, paper tables, CLI, FMI importer, MCAP),
# then, in a venv it creates itself (.venv, with the pinned maturin, ziglang and cargo-zigbuild on
# PATH), packs the FMUs with the library built for glibc 2.17, builds the Linux wheel of the Python
# package from them (its native module, the Rust log reader, built by maturin), installs it and runs
# the Python tests (fmpy, mcap, the wheel in a fresh venv).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage prints its time, so a slow stage shows where it is.
started=$SECONDS
stage_start=$SECONDS
in_stage=""
stage() {
  if [ -n "$in_stage" ]; then echo "   ($((SECONDS - stage_start)) s)"; fi
  in_stage=1
  stage_start=$SECONDS
  echo "== $*"
}

# The Python test environment's packages download and unpack while the Rust stages compile
# (mostly network and disk); the Python package itself, whose native module maturin builds,
# waits for `cargo test` (it reuses its compiled dependencies).
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r tests/python/requirements.txt \
  > .venv/requirements.log 2>&1 &
requirements=$!
trap 'kill "$requirements" 2>/dev/null || true' EXIT

stage "cargo fmt --check"
cargo fmt --all -- --check
stage "cargo clippy (beam-impact and the Python package's native module, python/native)"
cargo clippy --release --workspace --all-targets -- -D warnings
# --release: the dependencies' metadata is clippy's (the release profile), not checked again.
stage "cargo doc"
RUSTDOCFLAGS="-D warnings" cargo doc --release --workspace --no-deps --quiet
stage "cargo test --release (the library's unit tests, then one binary with every integration test)"
cargo test --release

stage "Python venv (.venv) with fmpy, mcap, maturin, ziglang and cargo-zigbuild"
if ! wait "$requirements"; then
  cat .venv/requirements.log
  echo "pip install -r tests/python/requirements.txt failed (its output above)" >&2
  exit 1
fi
# cargo-zigbuild finds zig through the venv's python (python3 -m ziglang).
export PATH="$PWD/.venv/bin:$PATH"

# The executable `cargo test` built; `pack` relinks the library against glibc 2.17 with zig,
# reusing the compiled dependencies.
stage "pack the FMUs and GangwayOnVessel.ssp (the library linked for glibc 2.17 by cargo-zigbuild's zig)"
bin="${CARGO_TARGET_DIR:-target}/release/beam-impact"
# --ssp: also GangwayOnVessel.ssp (the vessel-motion FMU compiled by the same zig; tests/python/test_ssp.py).
"$bin" pack --ssp --out target/fmu

# The wheel users install (docs/wheels.md), built once from the FMUs just packed (maturin links
# the native module for glibc 2.17, reusing the compiled dependencies), is the package the tests
# use: installed here, and into a fresh venv without Rust by tests/python/test_wheel.py.
stage "the Linux wheel (scripts/build-wheels.sh) into target/wheels and .venv"
rm -rf target/wheels
BEAM_IMPACT_WHEEL_TOOLS="$PWD/.venv" scripts/build-wheels.sh target/wheels --fmu-dir target/fmu
.venv/bin/python -m pip uninstall --quiet --yes beam_impact > /dev/null 2>&1 || true
.venv/bin/python -m pip install --quiet --disable-pip-version-check target/wheels/beam_impact-*.whl

# The HTML report's browser test (tests/python/test_html_report.py) drives Debian's chromium with
# Playwright: installed here where missing (CI runs as root), never by `playwright install`.
stage "chromium for the HTML report's browser test"
if ! command -v chromium > /dev/null; then
  mkdir -p target
  export DEBIAN_FRONTEND=noninteractive
  if ! { apt-get install -y chromium || { apt-get update && apt-get install -y chromium; }; } > target/chromium-install.log 2>&1; then
    cat target/chromium-install.log
    echo "apt-get install -y chromium failed (its output above)" >&2
    exit 1
  fi
fi
chromium --version 2> /dev/null

stage "pytest"
BEAM_IMPACT_FMU_DIR="$PWD/target/fmu" BEAM_IMPACT_BIN="$(cd "$(dirname "$bin")" && pwd)/beam-impact" \
  BEAM_IMPACT_REQUIRE_GLIBC_2_17=1 BEAM_IMPACT_REQUIRE_WHEEL=1 .venv/bin/python -m pytest -q tests/python
stage "all tests passed in $((SECONDS - started)) s"
