#!/bin/sh
# Installs the cross toolchain for the FMU's Windows binary into .cross/ (ignored), from the
# package registries only, without root and without touching the system or ~/.rustup:
#
#   - the Rust standard library's source matching the machine's rustc, from Debian's rust-src
#     package (unpacked, not installed) into .cross/sysroot, with the host's own libraries linked
#     in; .cross/bin/rustc runs the machine's rustc with --sysroot .cross/sysroot, so that
#     `cargo -Zbuild-std` (RUSTC_BOOTSTRAP=1) builds std for x86_64-pc-windows-gnu from it;
#   - zig (PyPI `ziglang`) as the C compiler and linker and `cargo-zigbuild`, in .cross/venv;
#   - with --wine: Debian bookworm's wine64 8.0 and the libraries it needs, unpacked into
#     .cross/wine (see scripts/wine-run.sh).
#
# Idempotent: what is there and matches the pins is kept; downloads are cached under
# ${XDG_CACHE_HOME:-~/.cache}/beam-impact-cross (debs/, wheels/) and checked against their SHA-256.
# Fails with one line naming what is missing or what to update.
#
# Usage: scripts/cross-toolchain.sh [--wine]
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CROSS=${BEAM_IMPACT_CROSS_DIR:-$ROOT/.cross}
CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
DEBIAN=${BEAM_IMPACT_DEBIAN_MIRROR:-http://deb.debian.org}

ZIGLANG_VERSION=0.17.0
CARGO_ZIGBUILD_VERSION=0.24.0

fail() {
    echo "cross-toolchain: $*" >&2
    exit 1
}

# rust-src per rustc release: Debian file (pool path under $DEBIAN/debian/) and SHA-256. The
# machine's rustc must match exactly: std's source uses the compiler's internals.
rust_src_pin() {
    case "$1" in
    1.95.0) echo "pool/main/r/rustc/rust-src_1.95.0+dfsg1-2~bpo13+1_all.deb 7b76db5b880a77f9e52975d2baa6209d2f76d2c9c2789515c3088cb960e2c83b" ;;
    *) return 1 ;;
    esac
}

for tool in rustc cargo python3 curl dpkg-deb tar sha256sum; do
    command -v "$tool" >/dev/null 2>&1 || fail "$tool is missing (needed to install the cross toolchain)"
done

# fetch URL FILE SHA256: downloads into the cache once, verified.
fetch() {
    mkdir -p "$(dirname "$2")"
    if [ -f "$2" ] && echo "$3  $2" | sha256sum -c --status; then
        return 0
    fi
    curl -fsSL --retry 3 -o "$2.part" "$1" || fail "cannot download $1 (superseded in Debian's archive? update the pin in scripts/cross-toolchain.sh)"
    echo "$3  $2.part" | sha256sum -c --status || fail "$1 does not match its pinned SHA-256 (update the pin in scripts/cross-toolchain.sh)"
    mv "$2.part" "$2"
    echo "cross-toolchain: downloaded $(basename "$2") ($(du -k "$2" | cut -f1) KiB)"
}

# --- the standard library's source and the sysroot -------------------------------------------
RUSTC_VERSION=$(rustc -V | cut -d' ' -f2)
PIN=$(rust_src_pin "$RUSTC_VERSION") ||
    fail "rustc $RUSTC_VERSION has no pinned rust-src: add Debian's rust-src_${RUSTC_VERSION}+dfsg* (trixie-backports or sid, pool/main/r/rustc/) to rust_src_pin in scripts/cross-toolchain.sh"
DEB_PATH=${PIN% *}
DEB_SHA=${PIN#* }
DEB="$CACHE/debs/$(basename "$DEB_PATH")"
HOST_SYSROOT=$(rustc --print sysroot)
HOST=$(rustc -vV | sed -n 's/^host: //p')
SYSROOT="$CROSS/sysroot"
STAMP="$SYSROOT/.rust-src"
if [ "$(cat "$STAMP" 2>/dev/null)" != "$DEB_SHA" ]; then
    fetch "$DEBIAN/debian/$DEB_PATH" "$DEB" "$DEB_SHA"
    rm -rf "$SYSROOT" "$CROSS/tmp"
    mkdir -p "$CROSS/tmp" "$SYSROOT/lib/rustlib/src/rust"
    dpkg-deb --fsys-tarfile "$DEB" | tar -x -C "$CROSS/tmp" --wildcards './usr/src/rustc-*/library'
    mv "$CROSS"/tmp/usr/src/rustc-*/library "$SYSROOT/lib/rustlib/src/rust/library"
    rm -rf "$CROSS/tmp"
    [ -f "$SYSROOT/lib/rustlib/src/rust/library/Cargo.lock" ] || fail "$DEB has no library/Cargo.lock"
    echo "$DEB_SHA" >"$STAMP"
fi
# The host's own std (build scripts, proc macros) comes from the machine's toolchain.
ln -sfn "$HOST_SYSROOT/lib/rustlib/$HOST" "$SYSROOT/lib/rustlib/$HOST"
mkdir -p "$CROSS/bin"
cat >"$CROSS/bin/rustc.new" <<EOF
#!/bin/sh
# The machine's rustc $RUSTC_VERSION with the standard library's source of $(basename "$DEB_PATH").
exec "$HOST_SYSROOT/bin/rustc" --sysroot "$SYSROOT" "\$@"
EOF
chmod +x "$CROSS/bin/rustc.new"
mv "$CROSS/bin/rustc.new" "$CROSS/bin/rustc"

# --- zig and cargo-zigbuild ----------------------------------------------------------------
VENV="$CROSS/venv"
WANT="ziglang==$ZIGLANG_VERSION cargo-zigbuild==$CARGO_ZIGBUILD_VERSION"
if [ "$(cat "$VENV/.pins" 2>/dev/null)" != "$WANT" ]; then
    mkdir -p "$CACHE/wheels"
    # shellcheck disable=SC2086
    if ! python3 -m pip download -q --only-binary :all: --dest "$CACHE/wheels" --no-index --find-links "$CACHE/wheels" $WANT 2>/dev/null; then
        # shellcheck disable=SC2086
        python3 -m pip download -q --only-binary :all: --dest "$CACHE/wheels" $WANT || fail "cannot download $WANT from PyPI"
    fi
    rm -rf "$VENV"
    python3 -m venv "$VENV" || fail "python3 -m venv failed (python3-venv missing?)"
    # shellcheck disable=SC2086
    "$VENV/bin/pip" install -q --no-index --find-links "$CACHE/wheels" $WANT || fail "cannot install $WANT into $VENV"
    echo "$WANT" >"$VENV/.pins"
fi

# --- wine64 (optional) ---------------------------------------------------------------------
if [ "${1:-}" = "--wine" ]; then
    "$ROOT/scripts/wine-toolchain.sh" "$CROSS" "$CACHE" "$DEBIAN"
fi

echo "cross-toolchain: ready in $CROSS (rustc $RUSTC_VERSION + $(basename "$DEB_PATH"), zig $ZIGLANG_VERSION, cargo-zigbuild $CARGO_ZIGBUILD_VERSION)"
