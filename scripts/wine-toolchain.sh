#!/bin/sh
# Unpacks Debian bookworm's wine64 8.0 (and libwine, libz-mingw-w64) into CROSS/wine without
# installing anything: `dpkg-deb -x`, downloads cached and checked against their SHA-256. The
# other libraries libwine names (ALSA, PulseAudio, gphoto2, pcap, OpenCL, ...) are only loaded by
# the Windows modules that need them, none of which a DLL test touches. Run it through
# scripts/wine-run.sh. Called by scripts/cross-toolchain.sh --wine.
#
# Usage: scripts/wine-toolchain.sh CROSS CACHE DEBIAN_MIRROR
set -eu
CROSS=$1
CACHE=$2
DEBIAN=$3

fail() {
    echo "wine-toolchain: $*" >&2
    exit 1
}

# Debian file (pool path) and SHA-256, bookworm main.
PINS="pool/main/w/wine/wine64_8.0~repack-4_amd64.deb 4ff56d97fb84c41dd450775f03ae42208f092e822f9baa742dcde951773ecb42
pool/main/w/wine/libwine_8.0~repack-4_amd64.deb 512b715f32fccf2ebec2b63f23d9d83394d30e27cc5570a8ef92c5d3627ef305
pool/main/libz/libz-mingw-w64/libz-mingw-w64_1.2.13+dfsg-1_all.deb b9e73ca486bc2aa66da86b5724220d2dd7c8299636b1df74c3414757a2170615"

WINE="$CROSS/wine"
STAMP=$(echo "$PINS" | sha256sum | cut -c1-16)
if [ "$(cat "$WINE/.pins" 2>/dev/null)" = "$STAMP" ]; then
    exit 0
fi
rm -rf "$WINE"
mkdir -p "$WINE/root" "$CACHE/debs"
echo "$PINS" | while read -r path sha; do
    deb="$CACHE/debs/$(basename "$path")"
    if ! { [ -f "$deb" ] && echo "$sha  $deb" | sha256sum -c --status; }; then
        curl -fsSL --retry 3 -o "$deb.part" "$DEBIAN/debian/$path" ||
            fail "cannot download $DEBIAN/debian/$path (superseded? update PINS in scripts/wine-toolchain.sh)"
        echo "$sha  $deb.part" | sha256sum -c --status || fail "$path does not match its pinned SHA-256"
        mv "$deb.part" "$deb"
        echo "wine-toolchain: downloaded $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"
    fi
    dpkg-deb -x "$deb" "$WINE/root"
done
[ -x "$WINE/root/usr/lib/wine/wine64" ] || fail "no usr/lib/wine/wine64 in the unpacked packages"
# Debian's wineserver script runs /usr/lib/wine/wineserver64; ours is beside it. (The loader finds
# the rest relative to itself; zlib1.dll, which user32 needs, comes through WINEDLLPATH.)
printf '#!/bin/sh\nexec "$(dirname "$0")/wineserver64" "$@"\n' >"$WINE/root/usr/lib/wine/wineserver"
echo "$STAMP" >"$WINE/.pins"
