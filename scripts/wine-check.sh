#!/bin/sh
# Proves the win64 DLL works: loads it under wine64 (scripts/cross-toolchain.sh --wine) with a
# small C importer built for Windows by zig (tests/wine/importer.c), runs the paper scenario
# through FMI 2 (instantiate with a file:///Z:/... resource URI, log.path "", initialise, step to
# 3 s in 1 ms steps) and compares the printed peaks with the same importer built for Linux
# against the Linux library: equal to 1e-12 relative, and says whether they are equal bit for bit.
#
# Usage: scripts/wine-check.sh [WINDOWS.dll [LINUX.so]]
#   defaults: target/cross/beam_impact.dll (scripts/cross-build.sh), target/release/libbeam_impact.so
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CROSS=${BEAM_IMPACT_CROSS_DIR:-$ROOT/.cross}
DLL=${1:-$ROOT/target/cross/beam_impact.dll}
SO=${2:-$ROOT/target/release/libbeam_impact.so}
WORK=$ROOT/target/cross/wine
WINE=$CROSS/wine/root

fail() {
    echo "wine-check: $*" >&2
    exit 1
}
[ -x "$WINE/usr/lib/wine/wine64" ] || fail "no wine64 in $CROSS/wine: run scripts/cross-toolchain.sh --wine"
[ -f "$DLL" ] || fail "no $DLL: run scripts/cross-build.sh"
[ -f "$SO" ] || fail "no $SO: run cargo build --release --lib"
command -v cc >/dev/null || fail "cc is missing (the Linux importer)"

ZIG="$CROSS/venv/bin/python -m ziglang"
mkdir -p "$WORK"
$ZIG cc -target x86_64-windows-gnu -O2 -o "$WORK/importer.exe" "$ROOT/tests/wine/importer.c"
$ZIG cc -target x86_64-windows-gnu -O2 -shared -o "$WORK/bcryptprimitives.dll" "$ROOT/tests/wine/bcryptprimitives.c" -ladvapi32
rm -f "$WORK"/*.lib "$WORK"/*.pdb
cc -O2 -o "$WORK/importer" "$ROOT/tests/wine/importer.c" -ldl
cp "$DLL" "$WORK/beam_impact.dll"

# The prefix (C:, the registry: ~700 MB, 10 s to 3 min to create) is kept in the cache across clones.
CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
export WINEPREFIX="$CACHE/wine-prefix-8.0" WINEDEBUG=-all WINEDLLPATH="$WINE/usr/x86_64-w64-mingw32/lib"
if [ ! -d "$WINEPREFIX" ]; then
    # Wait for wineboot's processes (wineserver -w): a prefix cut short at `wineserver -k` below
    # is updated again at the next run, which took 3 minutes.
    "$WINE/usr/lib/wine/wine64" wineboot --init >/dev/null 2>&1 || true
    "$WINE/usr/lib/wine/wineserver" -w || true
fi
# The DLL's folder as Wine sees it (Z: is /), and a resource URI in that form.
WIN_DIR="Z:$(echo "$WORK" | tr / '\\')"
URI="file:///Z:$WORK/resources"

"$WINE/usr/lib/wine/wine64" "$WORK/importer.exe" "$WIN_DIR\\beam_impact.dll" "$URI" >"$WORK/windows.txt" 2>"$WORK/windows.err" ||
    fail "the importer failed under wine: $(tail -3 "$WORK/windows.err" | tr '\n' ' ')"
"$WORK/importer" "$SO" "file://$WORK/resources" >"$WORK/linux.txt" 2>"$WORK/linux.err" ||
    fail "the importer failed on Linux: $(tail -3 "$WORK/linux.err" | tr '\n' ' ')"
"$WINE/usr/lib/wine/wineserver" -k 2>/dev/null || true

python3 - "$WORK/windows.txt" "$WORK/linux.txt" <<'EOF'
import sys
def read(path):
    return dict(line.split(" ", 1) for line in open(path).read().splitlines())
w, l = read(sys.argv[1]), read(sys.argv[2])
worst, bits = 0.0, True
for name in l:
    if name.startswith("peak."):
        a, b = float(w[name]), float(l[name])
        worst = max(worst, abs(a - b) / max(abs(b), 1e-300))
        bits &= w[name] == l[name]
        print(f"  {name:36s} windows {w[name]:>24s}  linux {l[name]:>24s}")
if worst > 1e-12:
    sys.exit(f"wine-check: the peaks differ, largest relative difference {worst:.3g} > 1e-12")
print(f"wine-check: the win64 DLL under wine agrees with the Linux library: largest relative difference {worst:.3g}"
      + (", bit for bit" if bits else ""))
EOF
