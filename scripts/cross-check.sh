#!/bin/sh
# The Windows cross build and its wine test in one command, for CI: installs the toolchain and
# wine64 (scripts/cross-toolchain.sh --wine; downloads cached), builds the Linux library (for the
# comparison) and the win64 DLL (scripts/cross-build.sh), runs both through the same FMI 2
# importer (scripts/wine-check.sh) and prints one verdict line with each stage's time.
#
# The toolchain and the cross build's directory are cached too, under ~/.cache/beam-impact-cross
# (toolchain/, target/; CI's fresh clone has no .cross/ or target/): std, the dependencies, zig's
# MinGW runtime and the wine prefix are built once, later runs compile this crate only.
#
# Usage: scripts/cross-check.sh
# Environment: BEAM_IMPACT_CROSS_DIR (toolchain, default ~/.cache/beam-impact-cross/toolchain), BEAM_IMPACT_CROSS_CACHE
# (downloads and the build directory, default ~/.cache/beam-impact-cross).
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
export BEAM_IMPACT_CROSS_CACHE="$CACHE"
# The toolchain lives in the cache too (not .cross/): a freshly installed zig rebuilds its MinGW C
# runtime at its first Windows link (3 minutes on two busy cores), a fresh sysroot moves std's path.
export BEAM_IMPACT_CROSS_DIR="${BEAM_IMPACT_CROSS_DIR:-$CACHE/toolchain}"
CROSS_TARGET=${BEAM_IMPACT_CROSS_TARGET:-$CACHE/target}

now() { date +%s; }
START=$(now)
TIMES=""
stage() {
    name=$1
    shift
    t0=$(now)
    if ! "$@"; then
        echo "cross-check: FAILED at $name after $(($(now) - START)) s" >&2
        exit 1
    fi
    TIMES="$TIMES $name $(($(now) - t0)) s,"
}

cd "$ROOT"
stage toolchain "$ROOT/scripts/cross-toolchain.sh" --wine
stage linux-lib cargo build --release --lib --quiet
stage windows-dll env BEAM_IMPACT_CROSS_TARGET="$CROSS_TARGET" "$ROOT/scripts/cross-build.sh" x86_64-pc-windows-gnu "$ROOT/target/cross/beam_impact.dll"
stage wine "$ROOT/scripts/wine-check.sh" "$ROOT/target/cross/beam_impact.dll" "$ROOT/target/release/libbeam_impact.so"
echo "cross-check: OK: win64 DLL built, exports the FMI functions only, imports system DLLs only, matches Linux under wine (${TIMES%,}; total $(($(now) - START)) s)"
