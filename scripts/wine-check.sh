#!/bin/sh
# Proves the win64 DLL works: loads it under wine64 (scripts/cross-toolchain.sh --wine) with a
# small C importer built for Windows by zig (tests/wine/importer.c), and runs the same importer
# built for Linux against the Linux library. Each runs the paper scenario through FMI 2 and then
# FMI 3: instantiate (resource URI file:///Z:/... under wine), log.path = a file in the work
# folder, initialise, step to 3 s in 1 ms steps; at 1.5 s get the state, serialize it, free it,
# deserialize it and set it back; at 3 s roll back to it and run 1.5-3 s again (the importer
# requires the same outputs bit for bit); terminate and free (which completes the MCAP log).
#
# Then it compares the two platforms: every printed value (the running peaks at 1.5 s and 3 s,
# the outputs at 3 s) to 1e-12 relative, saying whether they are equal bit for bit; the serialized
# states byte for byte (a portable format); and the MCAP logs byte for byte (scripts/mcap_compare.py:
# the log holds no field that may differ between platforms or runs, so nothing is masked; a
# difference is reported with the record, chunk, topic and message index where it starts).
#
# Usage: scripts/wine-check.sh [WINDOWS.dll [LINUX.so]]
#   defaults: target/cross/BeamImpact-windows.dll (what `beam-impact pack --platforms windows`
#   builds), target/release/libbeam_impact.so
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CROSS=${BEAM_IMPACT_CROSS_DIR:-$ROOT/.cross}
DLL=${1:-$ROOT/target/cross/BeamImpact-windows.dll}
SO=${2:-$ROOT/target/release/libbeam_impact.so}
WORK=$ROOT/target/cross/wine
WINE=$CROSS/wine/root

fail() {
    echo "wine-check: $*" >&2
    exit 1
}
[ -x "$WINE/usr/lib/wine/wine64" ] || fail "no wine64 in $CROSS/wine: run scripts/cross-toolchain.sh --wine"
[ -f "$DLL" ] || fail "no $DLL: run beam-impact pack --platforms windows (or scripts/cross-build.sh)"
[ -f "$SO" ] || fail "no $SO: run cargo build --release --lib"
command -v cc >/dev/null || fail "cc is missing (the Linux importer)"
SO=$(cd "$(dirname "$SO")" && pwd)/$(basename "$SO")

ZIG="$CROSS/venv/bin/python -m ziglang"
mkdir -p "$WORK"
$ZIG cc -target x86_64-windows-gnu -O2 -o "$WORK/importer.exe" "$ROOT/tests/wine/importer.c"
$ZIG cc -target x86_64-windows-gnu -O2 -shared -o "$WORK/bcryptprimitives.dll" "$ROOT/tests/wine/bcryptprimitives.c" -ladvapi32
rm -f "$WORK"/*.lib "$WORK"/*.pdb
cc -O2 -o "$WORK/importer" "$ROOT/tests/wine/importer.c" -ldl
cp "$DLL" "$WORK/beam_impact.dll"
# Both importers write their logs and states into the work folder (relative paths: it is the
# working directory of both), named windows-fmiN.* and linux-fmiN.*.
rm -f "$WORK"/windows-* "$WORK"/linux-*

# The prefix (C:, the registry: ~700 MB, 10 s to 3 min to create) is kept in the cache across clones.
CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
export WINEPREFIX="$CACHE/wine-prefix-8.0" WINEDEBUG=-all WINEDLLPATH="$WINE/usr/x86_64-w64-mingw32/lib"
# No Mono or Gecko installer prompts; wine's processes ended however this script ends.
export WINEDLLOVERRIDES="mscoree,mshtml="
trap '"$WINE/usr/lib/wine/wineserver" -k 2>/dev/null || true' EXIT
if [ ! -f "$WINEPREFIX/.ready" ]; then
    # Wait for wineboot's processes (wineserver -w): a prefix cut short at `wineserver -k` below
    # is updated again at the next run, which took 3 minutes. A prefix whose creation was cut
    # short (no .ready) is made again.
    rm -rf "$WINEPREFIX"
    timeout 900 "$WINE/usr/lib/wine/wine64" wineboot --init >/dev/null 2>&1 || true
    timeout 300 "$WINE/usr/lib/wine/wineserver" -w || true
    [ -f "$WINEPREFIX/system.reg" ] || fail "wineboot did not create the prefix $WINEPREFIX"
    touch "$WINEPREFIX/.ready"
fi
# The DLL's folder as Wine sees it (Z: is /), and a resource URI in that form.
WIN_DIR="Z:$(echo "$WORK" | tr / '\\')"
URI="file:///Z:$WORK/resources"

cd "$WORK"
t0=$(date +%s)
timeout 900 "$WINE/usr/lib/wine/wine64" importer.exe "$WIN_DIR\\beam_impact.dll" "$URI" windows >windows.txt 2>windows.err ||
    fail "the importer failed under wine: $(grep -v '^importer: fmi[23]: ' windows.err | tail -3 | tr '\n' ' ')"
t1=$(date +%s)
timeout 900 ./importer "$SO" "file://$WORK/resources" linux >linux.txt 2>linux.err ||
    fail "the importer failed on Linux: $(grep -v '^importer: fmi[23]: ' linux.err | tail -3 | tr '\n' ' ')"
t2=$(date +%s)
"$WINE/usr/lib/wine/wineserver" -k 2>/dev/null || true

# The printed values: the same names on both, numbers to 1e-12 relative, the rest equal.
python3 - windows.txt linux.txt values.txt <<'EOF' || exit 1
import sys
def read(path):
    lines = open(path).read().splitlines()
    odd = [line for line in lines if " " not in line]
    if odd:
        sys.exit(f"wine-check: {path} has a line without a value: {odd[0][:80]!r}")
    return dict(line.split(" ", 1) for line in lines)
w, l = read(sys.argv[1]), read(sys.argv[2])
if set(w) != set(l):
    sys.exit(f"wine-check: the importers printed different names: {sorted(set(w) ^ set(l))}")
worst, bits, peaks, n = 0.0, 0, 0, 0
for name in l:
    try:
        a, b = float(w[name]), float(l[name])
    except ValueError:
        if w[name] != l[name]:
            sys.exit(f"wine-check: {name} is \"{w[name]}\" under wine, \"{l[name]}\" on Linux")
        continue
    difference = abs(a - b) / max(abs(a), abs(b)) if a != b else 0.0
    if difference > 1e-12 or difference != difference:
        sys.exit(f"wine-check: {name} is {w[name]} under wine, {l[name]} on Linux: relative difference {difference:.3g} > 1e-12")
    worst = max(worst, difference)
    n += 1
    bits += w[name] == l[name]
    if ".peak." in name or ".at_save.peak." in name:
        peaks += 1
        print(f"  {name:46s} windows {w[name]:>24s}  linux {l[name]:>24s}")
open(sys.argv[3], "w").write(f"{peaks} {n} {bits} {worst:.3g}\n")
EOF
set -- $(cat values.txt)
PEAKS=$1 NVALUES=$2 BITS=$3 WORST=$4

# The serialized states: the portable byte format, the same bytes on every platform.
STATE_BYTES=0
for v in fmi2 fmi3; do
    cmp -s "windows-$v.state" "linux-$v.state" ||
        fail "the $v states serialized at 1.5 s differ: $(cmp "windows-$v.state" "linux-$v.state" 2>&1 | head -1)"
    STATE_BYTES=$((STATE_BYTES + $(wc -c <"linux-$v.state")))
done

# The MCAP logs, byte for byte.
LOG_BYTES=0
for v in fmi2 fmi3; do
    out=$(python3 "$ROOT/scripts/mcap_compare.py" "windows-$v.mcap" "linux-$v.mcap") || fail "the $v logs: ${out#mcap-compare: }"
    echo "  $v log: $out"
    LOG_BYTES=$((LOG_BYTES + $(wc -c <"linux-$v.mcap")))
done
rm -f windows-*.mcap linux-*.mcap

SAME="largest relative difference $WORST"
[ "$BITS" = "$NVALUES" ] && SAME="bit for bit"
echo "wine-check: OK: FMI 2 and FMI 3 under wine agree with Linux: $PEAKS peaks and $((NVALUES - PEAKS)) other values $SAME; serialized states $STATE_BYTES bytes and MCAP logs $LOG_BYTES bytes identical, 0 header bytes masked (wine $((t1 - t0)) s, Linux $((t2 - t1)) s)"
