#!/bin/sh
# Builds the FMU's library for another platform with the toolchain of scripts/cross-toolchain.sh,
# and checks the binary: it exports the FMI functions and nothing else, and links only the
# platform's system libraries.
#
#   x86_64-pc-windows-gnu     Windows x86-64 DLL (imports: system DLLs only, no MinGW runtime DLL)
#   x86_64-apple-darwin       macOS x86-64 dylib (Mach-O MH_DYLIB, macOS >= 10.12)
#   aarch64-apple-darwin      macOS arm64 dylib (macOS >= 11.0, ad-hoc code signature)
#   universal2-apple-darwin   both macOS dylibs merged into one fat (universal2) Mach-O, as an
#                             FMU's binaries/darwin64 needs: built one after the other, each as
#                             above, then merged by scripts/macho_info.py --merge (not by
#                             cargo-zigbuild's own universal2 target, which builds both in one
#                             cargo run with one MACOSX_DEPLOYMENT_TARGET and one target directory)
#
# Only this crate's cdylib is built (`cargo rustc --lib --crate-type cdylib`), std with it
# (-Zbuild-std), each target in its own cargo target directory ($BEAM_IMPACT_CROSS_TARGET/TRIPLE)
# so that builds of different targets never wait on each other's lock.
#
# Exports. rustc hands the linker the list of the cdylib's exports, and zig's linker ignores it on
# both platforms:
#   - Windows: the .def rustc passes as `-Wl,list.def` is ignored, and every symbol is exported
#     (4 300, mangled Rust and the C of lz4/zstd among them); a .def written here from the
#     source's FMI functions and given as an input file is honoured.
#   - macOS: cargo-zigbuild drops rustc's `-Wl,-exported_symbols_list,...` and zig 0.17 ignores it
#     anyway (no error, 3 165 exports), and rejects `-exported_symbol`. What is exported is every
#     global symbol of default visibility, so everything else is made hidden where it is compiled:
#     `-Zdefault-visibility=hidden` for every Rust crate and std (the `#[no_mangle] extern "C"`
#     FMI functions keep default visibility), `-fvisibility=hidden` for the C that cc-rs builds
#     (zstd-sys does that itself; lz4's headers mark its API `visibility("default")` unless
#     LZ4LIB_VISIBILITY/LZ4FLIB_VISIBILITY are defined, so they are defined empty). Four symbols
#     that are not ours stay exported and are allowed by name: `__mh_dylib_header` and
#     `___dso_handle`, which zig's linker makes (ld64 keeps them private), and std's weak
#     `___isPlatformVersionAtLeast`/`___isOSVersionAtLeast` (clang's `@available` runtime, in
#     std/src/sys/platform_version/darwin; `#[linkage = "weak"]` keeps default visibility whatever
#     -Zdefault-visibility says). Built on a Mac, rustc's export list would hide all four.
# Also for macOS: MACOSX_DEPLOYMENT_TARGET as rustc's own defaults (10.12, 11.0; zig would write
# 15.0); `-dead_strip_dylibs` (the libc crate links libiconv, for functions nothing here calls,
# and cargo-zigbuild adds libcharset); install name @rpath/<OUT's file name> (not the build path);
# CARGO_PROFILE_RELEASE_STRIP=false, as issue 18 found (rustc strips Apple binaries with an
# external tool after the link; the local symbols, about 0.8 MB a slice, stay).
#
# Usage: scripts/cross-build.sh TARGET OUT
# Environment: BEAM_IMPACT_CROSS_DIR (toolchain, default .cross), BEAM_IMPACT_CROSS_TARGET (build
# directories, default target/cross).
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CROSS=${BEAM_IMPACT_CROSS_DIR:-$ROOT/.cross}
TARGET_BASE=${BEAM_IMPACT_CROSS_TARGET:-$ROOT/target/cross}

fail() {
    echo "cross-build: $*" >&2
    exit 1
}
[ $# -eq 2 ] || fail "usage: scripts/cross-build.sh TARGET OUT (TARGET: x86_64-pc-windows-gnu, x86_64-apple-darwin, aarch64-apple-darwin or universal2-apple-darwin)"
TARGET=$1
OUT=$2
case "$TARGET" in
x86_64-pc-windows-gnu | x86_64-apple-darwin | aarch64-apple-darwin | universal2-apple-darwin) ;;
*) fail "unknown target $TARGET (x86_64-pc-windows-gnu, x86_64-apple-darwin, aarch64-apple-darwin or universal2-apple-darwin)" ;;
esac
[ -x "$CROSS/bin/rustc" ] && [ -x "$CROSS/venv/bin/cargo-zigbuild" ] ||
    fail "no cross toolchain in $CROSS: run scripts/cross-toolchain.sh"
[ "$("$CROSS/bin/rustc" -V)" = "$(rustc -V)" ] || fail "the machine's rustc changed: run scripts/cross-toolchain.sh"
mkdir -p "$(dirname "$OUT")"

# The FMI functions, from the source: every `extern "C" fn fmi2...`/`fmi3...` in src/fmi.
FMI=$(grep -rhoE 'extern "C" fn fmi[23][A-Za-z0-9_]+' "$ROOT/src/fmi" | sed 's/.* fn //' | sort -u)
WANT=$(echo "$FMI" | grep -c .)

# cargo_build TRIPLE [RUSTC ARGS...]: the cdylib for TRIPLE, in $TARGET_BASE/TRIPLE.
cargo_build() {
    triple=$1
    shift
    mkdir -p "$TARGET_BASE/$triple"
    (cd "$ROOT" && PATH="$CROSS/venv/bin:$PATH" RUSTC="$CROSS/bin/rustc" RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$TARGET_BASE/$triple" \
        cargo-zigbuild rustc --release --lib --crate-type cdylib --target "$triple" -Zbuild-std=std,panic_abort -- "$@")
}

# --- Windows ---------------------------------------------------------------------------------
if [ "$TARGET" = x86_64-pc-windows-gnu ]; then
    DEF="$TARGET_BASE/$TARGET/beam_impact.def"
    mkdir -p "$TARGET_BASE/$TARGET"
    {
        echo "LIBRARY beam_impact.dll"
        echo "EXPORTS"
        echo "$FMI" | sed 's/^/    /'
    } >"$DEF.new"
    mv "$DEF.new" "$DEF"
    cargo_build "$TARGET" -C link-arg="$DEF"
    BUILT="$TARGET_BASE/$TARGET/$TARGET/release/beam_impact.dll"
    [ -f "$BUILT" ] || fail "the build wrote no $BUILT"
    cp "$BUILT" "$OUT.new"
    mv "$OUT.new" "$OUT"
    # A binary that fails a check below is removed: nothing picks it up later as if checked.
    trap 'rm -f "$OUT"' EXIT

    # Exports and imports, read with the PE reader in scripts/pe_info.py (no binutils for PE needed).
    python3 "$ROOT/scripts/pe_info.py" "$OUT" >"$OUT.pe.txt"
    EXPORTS=$(sed -n 's/^export //p' "$OUT.pe.txt")
    N=$(echo "$EXPORTS" | grep -c . || true)
    OTHER=$(echo "$EXPORTS" | grep -v '^fmi[23]' || true)
    [ -z "$OTHER" ] || fail "the DLL exports $(echo "$OTHER" | wc -l) symbols besides the FMI functions, e.g. $(echo "$OTHER" | head -3 | tr '\n' ' ')"
    [ "$N" = "$WANT" ] || fail "the DLL exports $N FMI functions, the source declares $WANT"
    IMPORTS=$(sed -n 's/^import //p' "$OUT.pe.txt" | tr 'A-Z' 'a-z')
    BAD=$(echo "$IMPORTS" | grep -vE '^(kernel32|ntdll|ws2_32|userenv|bcryptprimitives|advapi32|bcrypt|api-ms-win-[a-z0-9-]+|ucrtbase|msvcrt)\.dll$' || true)
    [ -z "$BAD" ] || fail "the DLL imports non-system DLLs: $(echo "$BAD" | tr '\n' ' ')"
    trap - EXIT
    echo "cross-build: $OUT ($(du -k "$OUT" | cut -f1) KiB): exports $N FMI functions and nothing else; imports $(echo "$IMPORTS" | tr '\n' ' ')"
    exit 0
fi

# --- macOS -----------------------------------------------------------------------------------
NAME=$(basename "$OUT")
# Exported, not ours: see the header.
NOT_OURS='__mh_dylib_header|___dso_handle|___isPlatformVersionAtLeast|___isOSVersionAtLeast'

# build_darwin TRIPLE: the dylib for TRIPLE, at $TARGET_BASE/TRIPLE/TRIPLE/release/libbeam_impact.dylib.
build_darwin() (
    triple=$1
    case "$triple" in
    x86_64-*) export MACOSX_DEPLOYMENT_TARGET=10.12 ;;
    *) export MACOSX_DEPLOYMENT_TARGET=11.0 ;;
    esac
    export CARGO_PROFILE_RELEASE_STRIP=false
    export "CARGO_TARGET_$(echo "$triple" | tr 'a-z-' 'A-Z_')_RUSTFLAGS=-Zdefault-visibility=hidden"
    export "CFLAGS_$(echo "$triple" | tr '-' '_')=-fvisibility=hidden -DLZ4LIB_VISIBILITY= -DLZ4FLIB_VISIBILITY="
    cargo_build "$triple" -C link-arg=-Wl,-dead_strip_dylibs -C link-arg=-Wl,-install_name,@rpath/"$NAME"
    [ -f "$TARGET_BASE/$triple/$triple/release/libbeam_impact.dylib" ] || fail "the build wrote no $TARGET_BASE/$triple/$triple/release/libbeam_impact.dylib"
)

case "$TARGET" in
universal2-apple-darwin)
    TRIPLES="x86_64-apple-darwin aarch64-apple-darwin"
    ARCHS="x86_64 arm64"
    ;;
x86_64-apple-darwin)
    TRIPLES=$TARGET
    ARCHS=x86_64
    ;;
*)
    TRIPLES=$TARGET
    ARCHS=arm64
    ;;
esac
for t in $TRIPLES; do
    build_darwin "$t"
done
if [ "$TARGET" = universal2-apple-darwin ]; then
    python3 "$ROOT/scripts/macho_info.py" --merge "$OUT.new" \
        "$TARGET_BASE/x86_64-apple-darwin/x86_64-apple-darwin/release/libbeam_impact.dylib" \
        "$TARGET_BASE/aarch64-apple-darwin/aarch64-apple-darwin/release/libbeam_impact.dylib" ||
        fail "cannot merge the x86_64 and arm64 dylibs into $OUT"
else
    cp "$TARGET_BASE/$TARGET/$TARGET/release/libbeam_impact.dylib" "$OUT.new"
fi
mv "$OUT.new" "$OUT"
# A binary that fails a check below is removed: nothing picks it up later as if checked.
trap 'rm -f "$OUT"' EXIT

# Every slice, read with the Mach-O reader in scripts/macho_info.py (lines `ARCH KEY VALUE`).
python3 "$ROOT/scripts/macho_info.py" "$OUT" >"$OUT.macho.txt" || fail "scripts/macho_info.py cannot read $OUT"
GOT=$(sed -n 's/^slice \([^ ]*\) .*/\1/p' "$OUT.macho.txt" | tr '\n' ' ')
[ "$GOT" = "$ARCHS " ] || fail "$OUT has the slices ${GOT:-none}, not $ARCHS"
DYLIBS=""
SIGNED=""
for a in $ARCHS; do
    sed -n "s/^$a //p" "$OUT.macho.txt" >"$OUT.$a.txt"
    [ "$(sed -n 's/^filetype //p' "$OUT.$a.txt")" = MH_DYLIB ] || fail "the $a slice is a $(sed -n 's/^filetype //p' "$OUT.$a.txt"), not an MH_DYLIB"
    EXPORTS=$(sed -n 's/^export //p' "$OUT.$a.txt" | grep -vxE "$NOT_OURS" || true)
    N=$(echo "$EXPORTS" | grep -c . || true)
    OTHER=$(echo "$EXPORTS" | grep -v '^_fmi[23]' || true)
    [ -z "$OTHER" ] || fail "the $a slice exports $(echo "$OTHER" | wc -l) symbols besides the FMI functions, e.g. $(echo "$OTHER" | head -3 | tr '\n' ' ')"
    [ "$(echo "$EXPORTS" | sed 's/^_//' | sort -u)" = "$FMI" ] || fail "the $a slice exports $N FMI functions, the source declares $WANT (or other names)"
    D=$(sed -n 's/^dylib \([^ ]*\).*/\1/p' "$OUT.$a.txt")
    BAD=$(echo "$D" | grep -vxE '/usr/lib/(libSystem\.B|libiconv\.2|libcharset\.1|libresolv\.9)\.dylib|/System/Library/Frameworks/(CoreFoundation|Security)\.framework/Versions/A/(CoreFoundation|Security)' || true)
    [ -z "$BAD" ] || fail "the $a slice links non-system libraries: $(echo "$BAD" | tr '\n' ' ')"
    SIG=$(sed -n 's/^signature //p' "$OUT.$a.txt")
    case "$SIG" in
    none)
        [ "$a" != arm64 ] || fail "the arm64 slice has no code signature (LC_CODE_SIGNATURE): macOS on arm64 refuses to load it"
        SIG="no code signature"
        ;;
    "ok "*) SIG="$(echo "$SIG" | sed 's/^ok \([^(]*\) (.*/\1/') code signature (verified)" ;;
    *) fail "the $a slice's code signature does not verify: $SIG" ;;
    esac
    DYLIBS="$DYLIBS $(echo "$D" | tr '\n' ' ')"
    SIGNED="$SIGNED; $a: macOS >= $(sed -n 's/^minos \([^ ]*\).*/\1/p' "$OUT.$a.txt"), $SIG"
    rm -f "$OUT.$a.txt"
done
trap - EXIT
echo "cross-build: $OUT ($(du -k "$OUT" | cut -f1) KiB, $ARCHS): exports the $WANT FMI functions and nothing else of ours; links$(echo "$DYLIBS" | tr ' ' '\n' | sort -u | tr '\n' ' ' | sed 's/ $//')${SIGNED}"
