#!/bin/sh
# Issue 18 in one command, for CI (`.ci/run` runs it after tests/run_all.sh): installs the cross
# toolchain and wine64 (scripts/cross-toolchain.sh --wine; downloads cached), packs the FMUs for
# every platform (`beam-impact pack --platforms all`: Linux for glibc 2.17, the win64 DLL and the
# macOS universal2 dylib through scripts/cross-build.sh, which checks each one's exports and
# libraries), checks both FMUs (fmpy's validate_fmu, the binaries in each platform directory, the
# Mach-O slices with scripts/macho_info.py), and runs the DLL taken from the packed FMU under wine
# against the Linux library taken from it (scripts/wine-check.sh: FMI 2 and FMI 3, state
# serialization, MCAP logs byte for byte), then builds the abi3 wheels of Linux, Windows and macOS
# carrying those FMUs (scripts/build-wheels.sh --platforms all, each wheel checked by
# scripts/wheel_check.py). Prints `unzip -l` of both FMUs and one verdict line with each stage's time.
#
# The toolchain and the cross builds' directories are cached under ~/.cache/beam-impact-cross
# (toolchain/, target/<triple>/; CI's fresh clone has no .cross/ or target/): std, the
# dependencies, zig's C runtimes and the wine prefix are built once (a clean run took 21 minutes
# on two cores: pack 16, wine 4); later runs compile this crate only (warm: about 2 minutes).
#
# Usage: scripts/cross-check.sh
# Environment: BEAM_IMPACT_CROSS_DIR (toolchain, default ~/.cache/beam-impact-cross/toolchain),
# BEAM_IMPACT_CROSS_CACHE (downloads and build directories, default ~/.cache/beam-impact-cross).
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
export BEAM_IMPACT_CROSS_CACHE="$CACHE"
# The toolchain lives in the cache too (not .cross/): a freshly installed zig rebuilds its MinGW C
# runtime at its first Windows link (3 minutes on two busy cores), a fresh sysroot moves std's path.
export BEAM_IMPACT_CROSS_DIR="${BEAM_IMPACT_CROSS_DIR:-$CACHE/toolchain}"
export BEAM_IMPACT_CROSS_TARGET="${BEAM_IMPACT_CROSS_TARGET:-$CACHE/target}"
OUT=$ROOT/target/fmu-all
CHECK=$ROOT/target/cross/fmu-check

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

# fmpy for validate_fmu: the test venv when tests/run_all.sh made it, else one in the cache.
python_with_fmpy() {
    if [ -x "$ROOT/.venv/bin/python" ] && "$ROOT/.venv/bin/python" -c "import fmpy" 2>/dev/null; then
        PYTHON=$ROOT/.venv/bin/python
        return 0
    fi
    PYTHON=$CACHE/fmpy-venv/bin/python
    if ! "$PYTHON" -c "import fmpy" 2>/dev/null; then
        python3 -m venv "$CACHE/fmpy-venv" &&
            "$PYTHON" -m pip install --quiet --disable-pip-version-check "$(grep '^fmpy==' "$ROOT/tests/python/requirements.txt")"
    fi
}

# Both FMUs: fmpy's validation, each platform directory holding its binary (FMI 3: one macOS
# slice per directory, each checked again), unzip -l for the record; the DLL and the Linux library
# taken out of the FMI 3 FMU for the wine test.
check_fmus() {
    rm -rf "$CHECK"
    mkdir -p "$CHECK"
    for fmi in fmi2 fmi3; do
        echo "--- unzip -l target/fmu-all/$fmi/BeamImpact.fmu"
        unzip -l "$OUT/$fmi/BeamImpact.fmu" || return 1
    done
    "$PYTHON" - "$OUT" "$CHECK" <<'EOF' || return 1
import sys, zipfile
from pathlib import Path
from fmpy import supported_platforms
from fmpy.validation import validate_fmu
out, check = Path(sys.argv[1]), Path(sys.argv[2])
want = {
    "fmi2": ["binaries/linux64/BeamImpact.so", "binaries/win64/BeamImpact.dll", "binaries/darwin64/BeamImpact.dylib"],
    "fmi3": ["binaries/x86_64-linux/BeamImpact.so", "binaries/x86_64-windows/BeamImpact.dll",
             "binaries/x86_64-darwin/BeamImpact.dylib", "binaries/aarch64-darwin/BeamImpact.dylib"],
}
for fmi, binaries in want.items():
    fmu = out / fmi / "BeamImpact.fmu"
    problems = validate_fmu(str(fmu))
    if problems:
        sys.exit(f"cross-check: fmpy's validate_fmu on {fmu}: {problems}")
    with zipfile.ZipFile(fmu) as archive:
        names = set(archive.namelist())
        missing = [b for b in binaries if b not in names]
        if missing:
            sys.exit(f"cross-check: {fmu} lacks {missing}")
        extra = sorted(n for n in names if n.startswith("binaries/") and n not in binaries)
        if extra:
            sys.exit(f"cross-check: {fmu} holds unexpected binaries {extra}")
        for b in binaries:
            archive.extract(b, check / fmi)
    print(f"cross-check: {fmi}: validate_fmu finds nothing; platforms {supported_platforms(str(fmu))}")
EOF
    # The packed Linux library: glibc 2.17 symbols at most (manylinux2014), as tests/python/test_glibc.py asks.
    glibc=$(objdump -T "$CHECK/fmi3/binaries/x86_64-linux/BeamImpact.so" | grep -o 'GLIBC_[0-9.]*' | sort -t. -k2,2n -k3,3n -u | tail -1)
    [ -n "$glibc" ] || { echo "cross-check: no GLIBC symbol version found in the packed Linux library (objdump -T)" >&2; return 1; }
    case "$glibc" in
    GLIBC_2.[0-9] | GLIBC_2.[0-9].* | GLIBC_2.1[0-7] | GLIBC_2.1[0-7].*) echo "cross-check: x86_64-linux needs $glibc at most" ;;
    *) echo "cross-check: the packed Linux library needs $glibc, newer than GLIBC_2.17" >&2 && return 1 ;;
    esac
    python3 "$ROOT/scripts/macho_info.py" --self-test >/dev/null || return 1
    for slice in x86_64 aarch64; do
        info=$(python3 "$ROOT/scripts/macho_info.py" "$CHECK/fmi3/binaries/$slice-darwin/BeamImpact.dylib") || return 1
        echo "$info" | grep -q " filetype MH_DYLIB$" || { echo "cross-check: fmi3 $slice-darwin is not a dylib" >&2; return 1; }
        echo "$info" | grep -E " (filetype|minos|dylib|signature|exports) " | sed "s|^|cross-check: fmi3 $slice-darwin: |"
    done
    info=$(python3 "$ROOT/scripts/macho_info.py" "$CHECK/fmi3/binaries/aarch64-darwin/BeamImpact.dylib") || return 1
    echo "$info" | grep -q "^arm64 signature ok" || { echo "cross-check: the packed arm64 slice's code signature does not verify" >&2; return 1; }
}

cd "$ROOT"
stage toolchain "$ROOT/scripts/cross-toolchain.sh" --wine
stage host-build cargo build --release --quiet
# cargo-zigbuild from the toolchain's venv: pack links the Linux library for glibc 2.17 too.
stage pack env PATH="$BEAM_IMPACT_CROSS_DIR/venv/bin:$PATH" "$ROOT/target/release/beam-impact" pack --platforms all --out "$OUT"
stage fmpy python_with_fmpy
stage fmu-check check_fmus
# The wheels of every platform (issue 31), each carrying the FMUs just checked; the Linux one is
# also built (and run) by tests/run_all.sh. maturin in a venv of the cache, not of the clone: its
# zig wrappers (the C compiler of lz4-sys and zstd-sys) are named after maturin's path, and a new
# path would rebuild the C and what depends on it for both macOS slices.
wheels() {
    export BEAM_IMPACT_WHEEL_TOOLS="${BEAM_IMPACT_WHEEL_TOOLS:-$CACHE/wheel-tools}"
    rm -rf "$ROOT/target/wheels-all"
    "$ROOT/scripts/build-wheels.sh" "$ROOT/target/wheels-all" --platforms all --fmu-dir "$OUT"
}
stage wine "$ROOT/scripts/wine-check.sh" "$CHECK/fmi3/binaries/x86_64-windows/BeamImpact.dll" "$CHECK/fmi3/binaries/x86_64-linux/BeamImpact.so"
stage wheels wheels
echo "cross-check: OK: both FMUs carry Linux, Windows and macOS (universal2) binaries, pass validate_fmu and the binary checks; the packed DLL matches the packed Linux library under wine; the abi3 wheels of the three platforms carry them and pass scripts/wheel_check.py (${TIMES%,}; total $(($(now) - START)) s)"
