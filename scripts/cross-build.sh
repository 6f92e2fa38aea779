#!/bin/sh
# Builds the FMU's library for Windows x86-64 (x86_64-pc-windows-gnu) with the toolchain of
# scripts/cross-toolchain.sh, and checks the DLL: it exports the FMI functions and nothing else,
# and imports only system DLLs (no libgcc_s, libwinpthread or other MinGW runtime DLL).
#
# Only this crate's cdylib is built (`cargo rustc --lib --crate-type cdylib`), std with it
# (-Zbuild-std). The exports come from a .def file written here from the source's FMI functions:
# zig's linker ignores the .def rustc passes as `-Wl,list.def` and then exports every symbol (4 300,
# mangled Rust and the C of lz4/zstd among them); a .def given as an input file is honoured.
#
# Usage: scripts/cross-build.sh [OUT.dll]   (default target/cross/beam_impact.dll)
# Environment: CARGO_TARGET_DIR (default target/cross).
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CROSS=${BEAM_IMPACT_CROSS_DIR:-$ROOT/.cross}
TARGET=x86_64-pc-windows-gnu
TARGET_DIR=${CARGO_TARGET_DIR:-$ROOT/target/cross}
OUT=${1:-$TARGET_DIR/beam_impact.dll}

fail() {
    echo "cross-build: $*" >&2
    exit 1
}
[ -x "$CROSS/bin/rustc" ] && [ -x "$CROSS/venv/bin/cargo-zigbuild" ] ||
    fail "no cross toolchain in $CROSS: run scripts/cross-toolchain.sh"
[ "$("$CROSS/bin/rustc" -V)" = "$(rustc -V)" ] || fail "the machine's rustc changed: run scripts/cross-toolchain.sh"

# The FMI functions, from the source: every `extern "C" fn fmi2...`/`fmi3...` in src/fmi.
mkdir -p "$TARGET_DIR"
DEF="$TARGET_DIR/beam_impact.def"
{
    echo "LIBRARY beam_impact.dll"
    echo "EXPORTS"
    grep -rhoE 'extern "C" fn fmi[23][A-Za-z0-9_]+' "$ROOT/src/fmi" | sed 's/.* fn /    /' | sort -u
} >"$DEF.new"
mv "$DEF.new" "$DEF"
WANT=$(grep -c '^    fmi' "$DEF")

cd "$ROOT"
PATH="$CROSS/venv/bin:$PATH" RUSTC="$CROSS/bin/rustc" RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$TARGET_DIR" \
    cargo-zigbuild rustc --release --lib --crate-type cdylib --target "$TARGET" -Zbuild-std=std,panic_abort \
    -- -C link-arg="$DEF"
BUILT="$TARGET_DIR/$TARGET/release/beam_impact.dll"
[ -f "$BUILT" ] || fail "the build wrote no $BUILT"
cp "$BUILT" "$OUT.new"
mv "$OUT.new" "$OUT"

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
echo "cross-build: $OUT ($(du -k "$OUT" | cut -f1) KiB): exports $N FMI functions and nothing else; imports $(echo "$IMPORTS" | tr '\n' ' ')"
