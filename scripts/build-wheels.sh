#!/bin/sh
# Builds the beam_impact Python package's wheels (issue 31, item 2): one abi3 wheel per platform
# (CPython >= 3.9), each carrying the native module (python/native, the crate's log reader and
# checks) and the packed FMUs (beam_impact/fmus/fmi2/BeamImpact.fmu and fmi3/, which
# `beam_impact.fmu_path()` finds), so that `pip install WHEEL` needs no Rust.
#
#   linux (default)  beam_impact-V-cp39-abi3-manylinux_2_17_x86_64.manylinux2014_x86_64.whl: the
#                    module linked against glibc 2.17 by zig; the FMUs carry the Linux library.
#   all              also beam_impact-V-cp39-abi3-win_amd64.whl (x86_64-pc-windows-gnu, importing
#                    python3.dll, the abi3 one, and system DLLs only) and
#                    beam_impact-V-cp39-abi3-macosx_10_12_x86_64.macosx_11_0_arm64.macosx_10_12_universal2.whl
#                    (x86_64 and arm64 in one Mach-O); every wheel's FMUs then carry the Linux,
#                    Windows and macOS binaries (`beam-impact pack --platforms all`).
#
# Tools: maturin, ziglang and cargo-zigbuild, pinned in tests/python/requirements.txt, in the venv
# $BEAM_IMPACT_WHEEL_TOOLS (default target/wheel-tools, made here). The Linux
# module is the host build of python/native linked by zig (`maturin build -- -C linker=...`: only
# the link differs, so `cargo build --release`'s compiled dependencies are reused, as `beam-impact
# pack` does for the FMU). Windows and macOS use the cross toolchain of scripts/cross-toolchain.sh
# (std built from source, -Zbuild-std; directories as scripts/cross-check.sh caches them).
#
# Every wheel is checked before it is kept (scripts/wheel_check.py): its name's and WHEEL's tags,
# the FMUs inside, the native module's exports and imports (Windows: PyInit__native alone,
# python3.dll and system DLLs; macOS: both slices, no libpython; Linux: GLIBC_2.17 at most, no
# libpython). A wheel failing a check is removed.
#
# With --fmu-dir DIR the FMUs are taken from DIR/fmi2/BeamImpact.fmu and DIR/fmi3/ (packed before,
# for the same platforms) instead of being packed here: tests/run_all.sh builds the Linux wheel so
# from the FMUs it has just packed, and no library is built twice.
#
# Usage: scripts/build-wheels.sh OUT_DIR [--platforms linux|all] [--fmu-dir DIR]
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)

fail() {
    echo "build-wheels: $*" >&2
    exit 1
}
usage="usage: scripts/build-wheels.sh OUT_DIR [--platforms linux|all] [--fmu-dir DIR]"
[ $# -ge 1 ] || fail "$usage"
OUT=$1
shift
PLATFORMS=linux
FMU_DIR=""
while [ $# -gt 0 ]; do
    case "$1" in
    --platforms)
        [ $# -ge 2 ] || fail "$usage"
        PLATFORMS=$2
        shift 2
        ;;
    --fmu-dir)
        [ $# -ge 2 ] || fail "$usage"
        FMU_DIR=$2
        shift 2
        ;;
    --platforms=*)
        PLATFORMS=${1#--platforms=}
        shift
        ;;
    *) fail "unknown argument $1 ($usage)" ;;
    esac
done
case "$PLATFORMS" in
linux | all) ;;
*) fail "--platforms takes linux or all, got $PLATFORMS" ;;
esac
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

now() { date +%s; }
START=$(now)
TARGET_DIR=${CARGO_TARGET_DIR:-$ROOT/target}
STAGE=$TARGET_DIR/wheel-stage
TOOLS=${BEAM_IMPACT_WHEEL_TOOLS:-$TARGET_DIR/wheel-tools}

# --- tools ---------------------------------------------------------------------------------
# maturin, ziglang and cargo-zigbuild at the pins of tests/python/requirements.txt, in TOOLS: a venv
# made here (target/wheel-tools, or BEAM_IMPACT_WHEEL_TOOLS when that does not exist yet) or one
# given that has them (tests/run_all.sh gives its .venv).
pin() {
    grep -E "^$1==" "$ROOT/tests/python/requirements.txt" | sed 's/[[:space:]].*//' | grep . ||
        fail "tests/python/requirements.txt pins no $1"
}
WANT="$(pin maturin) $(pin ziglang) $(pin cargo-zigbuild)"
has_pins() {
    # shellcheck disable=SC2086
    "$TOOLS/bin/python" - $WANT <<'EOF' 2>/dev/null
import sys
from importlib.metadata import version
sys.exit(any(version(name) != want for name, want in (p.split("==") for p in sys.argv[1:])))
EOF
}
if ! has_pins; then
    # A folder given that exists is never removed (it may be the test venv): only made when absent.
    [ -z "${BEAM_IMPACT_WHEEL_TOOLS:-}" ] || [ ! -e "$TOOLS" ] ||
        fail "BEAM_IMPACT_WHEEL_TOOLS=$TOOLS is not a venv with $WANT"
    rm -rf "$TOOLS"
    python3 -m venv "$TOOLS" || fail "python3 -m venv failed (python3-venv missing?)"
    # shellcheck disable=SC2086
    "$TOOLS/bin/python" -m pip install --quiet --disable-pip-version-check $WANT || fail "cannot install $WANT into $TOOLS"
fi
MATURIN=$TOOLS/bin/maturin

# --- the FMUs --------------------------------------------------------------------------------
if [ "$PLATFORMS" = all ]; then
    CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
    export BEAM_IMPACT_CROSS_CACHE="$CACHE"
    export BEAM_IMPACT_CROSS_DIR="${BEAM_IMPACT_CROSS_DIR:-$CACHE/toolchain}"
    export BEAM_IMPACT_CROSS_TARGET="${BEAM_IMPACT_CROSS_TARGET:-$CACHE/target}"
    "$ROOT/scripts/cross-toolchain.sh" >/dev/null || fail "scripts/cross-toolchain.sh failed"
    PACK_PLATFORMS=all
else
    PACK_PLATFORMS=linux
fi
rm -rf "$STAGE"
mkdir -p "$STAGE"
if [ -z "$FMU_DIR" ]; then
    (cd "$ROOT" && cargo build --release --quiet --bin beam-impact) || fail "cargo build --release failed"
    PATH="$TOOLS/bin:$PATH" "$TARGET_DIR/release/beam-impact" pack --platforms "$PACK_PLATFORMS" --out "$STAGE/fmu" ||
        fail "beam-impact pack --platforms $PACK_PLATFORMS failed"
    FMU_DIR=$STAGE/fmu
fi
for fmi in fmi2 fmi3; do
    [ -f "$FMU_DIR/$fmi/BeamImpact.fmu" ] || fail "no $FMU_DIR/$fmi/BeamImpact.fmu (--fmu-dir: pack it first)"
done

# The FMUs go into the package's source folder for maturin (which packs python/beam_impact as
# it finds it; /python/beam_impact/fmus/ is ignored by git) and are removed again on exit.
# The example scenarios (and the motion file one names) go in beside them, for
# `beam_impact.examples()` from a wheel (/python/beam_impact/examples/ is ignored by git too).
# The Linux wheel's `beam-impact` command goes into maturin's data folder, made for that wheel
# alone (below): python/beam_impact._native.data/ (ignored by git), maturin's default
# `<module-name>.data`, which it packs when present and skips when absent (a `data =` setting in
# pyproject.toml would fail `pip install ./python`, which carries no command).
FMUS=$ROOT/python/beam_impact/fmus
EXAMPLES=$ROOT/python/beam_impact/examples
DATA=$ROOT/python/beam_impact._native.data
SCRIPTS=$DATA/scripts
cleanup() { rm -rf "$FMUS" "$EXAMPLES" "$DATA"; }
trap cleanup EXIT
trap 'cleanup; exit 130' INT TERM
rm -rf "$FMUS" "$EXAMPLES" "$DATA"
for fmi in fmi2 fmi3; do
    mkdir -p "$FMUS/$fmi"
    cp "$FMU_DIR/$fmi/BeamImpact.fmu" "$FMUS/$fmi/BeamImpact.fmu"
done
mkdir -p "$EXAMPLES"
cp "$ROOT"/examples/*.toml "$ROOT"/examples/*.csv "$EXAMPLES/"

VERSION=$(sed -n 's/^version = "\(.*\)"$/\1/p' "$ROOT/python/pyproject.toml" | head -1)
BUILT=""
# keep WHEEL PLATFORM: checks the wheel maturin wrote (scripts/wheel_check.py), then keeps it in OUT.
keep() {
    python3 "$ROOT/scripts/wheel_check.py" "$1" "$2" "$PACK_PLATFORMS" || {
        rm -f "$1"
        fail "$(basename "$1") fails its checks (above); removed"
    }
    BUILT="$BUILT $(basename "$1")"
}
# maturin_build DIR [ARGS...]: one wheel into the empty DIR; prints its path.
maturin_build() {
    dir=$1
    shift
    rm -rf "$dir"
    mkdir -p "$dir"
    (cd "$ROOT/python" && "$MATURIN" build --release --quiet --out "$dir" "$@") >&2 || return 1
    set -- "$dir"/*.whl
    [ $# -eq 1 ] && [ -f "$1" ] || return 1
    echo "$1"
}

# --- Linux: the host build, linked by zig against glibc 2.17's symbols -------------------------
t0=$(now)
LINKER=$STAGE/zigcc-x86_64-linux-gnu.2.17.sh
cat >"$LINKER" <<EOF
#!/bin/sh
# Written by scripts/build-wheels.sh: links with zig against glibc 2.17's symbols (manylinux2014).
exec '$TOOLS/bin/cargo-zigbuild' zig cc -- -g -fno-sanitize=all -target x86_64-linux-gnu.2.17 "\$@"
EOF
chmod +x "$LINKER"
# The `beam-impact` command, as ruff's and uv's wheels carry theirs: the release executable linked
# by the same zig for glibc 2.17 (`cargo rustc --bin`: the crate's library and every dependency
# are the host build's; only the executable's own crate is compiled and linked again, about 5 s;
# it replaces target/release/beam-impact, the same code, until the next `cargo build` relinks
# it). After `beam-impact pack` (whose `cargo rustc --lib` leaves the library's build with its
# linker argument) this step recompiles the library once, 100 s in tests/run_all.sh, which the
# native module's build below then reuses (it took as long without this step). The executable
# goes into the data folder's scripts/ (the wheel's `beam_impact-V.data/scripts/`), whose files
# pip installs into the environment's bin/, on its PATH. The Linux wheel only: the Windows and
# macOS wheels carry no command (the executable is not cross-built).
t1=$(now)
(cd "$ROOT" && PATH="$TOOLS/bin:$PATH" cargo rustc --release --quiet --bin beam-impact -- -C linker="$LINKER") ||
    fail "cargo rustc --release --bin beam-impact (linked for glibc 2.17) failed"
mkdir -p "$SCRIPTS"
cp "$TARGET_DIR/release/beam-impact" "$SCRIPTS/beam-impact"
chmod 755 "$SCRIPTS/beam-impact"
echo "build-wheels: the beam-impact command in $(($(now) - t1)) s"
WHEEL=$(PATH="$TOOLS/bin:$PATH" maturin_build "$STAGE/linux" --compatibility manylinux2014 --auditwheel check \
    -- -C linker="$LINKER") || fail "maturin build for Linux failed"
rm -rf "$DATA"
mv "$WHEEL" "$OUT/"
keep "$OUT/$(basename "$WHEEL")" linux
echo "build-wheels: linux in $(($(now) - t0)) s"

if [ "$PLATFORMS" = all ]; then
    CROSS=$BEAM_IMPACT_CROSS_DIR
    [ "$("$CROSS/bin/rustc" -V)" = "$(rustc -V)" ] || fail "the machine's rustc changed: run scripts/cross-toolchain.sh"
    # cross_build TRIPLE DIR [MATURIN ARGS...]: maturin with the cross toolchain (zig from its venv,
    # std from source), in the target directory scripts/cross-build.sh uses for TRIPLE.
    cross_build() {
        triple=$1
        dir=$2
        shift 2
        PATH="$CROSS/venv/bin:$TOOLS/bin:$PATH" RUSTC="$CROSS/bin/rustc" RUSTC_BOOTSTRAP=1 \
            CARGO_TARGET_DIR="$BEAM_IMPACT_CROSS_TARGET/$triple" \
            maturin_build "$dir" --target "$triple" -Z build-std=std,panic_abort "$@"
    }

    # --- Windows: python3.dll's import library from pyo3 (generate-import-lib, with zig's dlltool);
    # the one export named in a .def file (zig's linker ignores rustc's export list and would export
    # every symbol). Not maturin's --zig: for this mixed package it adds, to every crate's
    # RUSTFLAGS, a .def exporting `PyInit_beam_impact._native`, which no crate defines (the link of
    # the crate's own cdylib fails). Instead maturin's `cargo rustc` goes through cargo-zigbuild (a
    # `cargo` on PATH that hands `rustc` to it), which links with zig as scripts/cross-build.sh does.
    t0=$(now)
    DEF=$STAGE/native.def
    printf 'LIBRARY _native.pyd\nEXPORTS\n    PyInit__native\n' >"$DEF"
    mkdir -p "$STAGE/cargo-zigbuild"
    cat >"$STAGE/cargo-zigbuild/cargo" <<EOF
#!/bin/sh
# Written by scripts/build-wheels.sh: maturin's \`cargo rustc\` through cargo-zigbuild, the rest to cargo.
if [ "\$1" = rustc ] && [ -z "\${BEAM_IMPACT_IN_ZIGBUILD:-}" ]; then
    shift
    BEAM_IMPACT_IN_ZIGBUILD=1 exec cargo-zigbuild rustc "\$@"
fi
exec '$(command -v cargo)' "\$@"
EOF
    chmod +x "$STAGE/cargo-zigbuild/cargo"
    WHEEL=$(PATH="$STAGE/cargo-zigbuild:$PATH" ZIG_COMMAND="$CROSS/venv/bin/python3 -m ziglang" \
        cross_build x86_64-pc-windows-gnu "$STAGE/windows" -- -C link-arg="$DEF") ||
        fail "maturin build for x86_64-pc-windows-gnu failed"
    mv "$WHEEL" "$OUT/"
    keep "$OUT/$(basename "$WHEEL")" windows
    echo "build-wheels: windows in $(($(now) - t0)) s"

    # --- macOS: each slice as scripts/cross-build.sh builds the FMU's dylib (its header says why:
    # hidden default visibility, the deployment targets, no strip), then one universal2 wheel.
    t0=$(now)
    for triple in x86_64-apple-darwin aarch64-apple-darwin; do
        WHEEL=$(
            case "$triple" in
            x86_64-*) export MACOSX_DEPLOYMENT_TARGET=10.12 ;;
            *) export MACOSX_DEPLOYMENT_TARGET=11.0 ;;
            esac
            export CARGO_PROFILE_RELEASE_STRIP=false
            export "CARGO_TARGET_$(echo "$triple" | tr 'a-z-' 'A-Z_')_RUSTFLAGS=-Zdefault-visibility=hidden"
            export "CFLAGS_$(echo "$triple" | tr '-' '_')=-fvisibility=hidden -DLZ4LIB_VISIBILITY= -DLZ4FLIB_VISIBILITY="
            cross_build "$triple" "$STAGE/$triple" --zig -- -C link-arg=-Wl,-dead_strip_dylibs
        ) || fail "maturin build for $triple failed"
    done
    WHEEL=$(python3 "$ROOT/scripts/wheel_universal2.py" "$STAGE"/x86_64-apple-darwin/*.whl \
        "$STAGE"/aarch64-apple-darwin/*.whl "$OUT") || fail "cannot merge the macOS wheels into a universal2 one"
    keep "$WHEEL" macos
    echo "build-wheels: macos in $(($(now) - t0)) s"
fi

echo "build-wheels: OK: version $VERSION, FMUs for $PACK_PLATFORMS, in $OUT:$(echo "$BUILT" | sed 's/ /\n  /g') (total $(($(now) - START)) s)"
