#!/usr/bin/env python3
"""Reads a Mach-O file, thin or fat (universal), and prints what scripts/cross-build.sh checks, one
fact a line (standard library only, like pe_info.py):

    file fat 2 slices | file thin
    slice ARCH offset N size N align 2^K       one per slice (thin: offset 0, no align)
    ARCH filetype MH_DYLIB                      then, for each slice, lines starting with its arch:
    ARCH cpu x86_64 subtype 3
    ARCH flags NOUNDEFS DYLDLINK ...
    ARCH minos 10.12 sdk 27.0 (LC_VERSION_MIN_MACOSX)     or (LC_BUILD_VERSION platform macos)
    ARCH id @rpath/NAME.dylib                   LC_ID_DYLIB
    ARCH dylib PATH (LC_LOAD_DYLIB compatibility 1.0.0 current 1359.0.0)   every linked dylib
    ARCH rpath PATH
    ARCH loadcmds LC_SEGMENT_64 LC_SEGMENT_64 ...
    ARCH signature none | ok ad-hoc linker-signed (sha256, N pages of 4096 bytes, ...) | invalid: WHY
    ARCH exports N (export trie; the symbol table's external defined symbols agree)
    ARCH export _NAME                           the Mach-O names (C names with a leading underscore)

The exports are those of the export trie (what dyld resolves), compared with the symbol table's
external defined symbols; a difference is reported on the `exports` line. The code signature's
CodeDirectory hashes are recomputed over the slice (code slots and the special slots whose blob
is present), so `ok` means the signature matches the bytes, as the kernel checks on arm64.

    macho_info.py FILE                     prints the above
    macho_info.py --merge OUT THIN1 THIN2  writes a fat binary of thin Mach-O files (one per CPU
                                           type; slices aligned to 2^14, as lipo does for arm64)
    macho_info.py --self-test              merges and reads synthetic dylibs (no toolchain needed)
"""

import hashlib
import os
import struct
import sys

FAT_MAGIC, FAT_MAGIC_64 = 0xCAFEBABE, 0xCAFEBABF
MH_MAGIC_64 = 0xFEEDFACF
CPU_TYPES = {0x01000007: "x86_64", 0x0100000C: "arm64", 7: "i386", 12: "arm"}
FILETYPES = {1: "MH_OBJECT", 2: "MH_EXECUTE", 6: "MH_DYLIB", 7: "MH_DYLINKER", 8: "MH_BUNDLE", 10: "MH_DSYM"}
HEADER_FLAGS = [
    (0x1, "NOUNDEFS"), (0x4, "DYLDLINK"), (0x80, "TWOLEVEL"), (0x8000, "WEAK_DEFINES"),
    (0x10000, "BINDS_TO_WEAK"), (0x100000, "NO_REEXPORTED_DYLIBS"), (0x200000, "PIE"),
    (0x800000, "HAS_TLV_DESCRIPTORS"), (0x2000000, "APP_EXTENSION_SAFE"),
]
LC_REQ_DYLD = 0x80000000
LOAD_COMMANDS = {
    0x1: "LC_SEGMENT", 0x2: "LC_SYMTAB", 0xB: "LC_DYSYMTAB", 0xC: "LC_LOAD_DYLIB", 0xD: "LC_ID_DYLIB",
    0xE: "LC_LOAD_DYLINKER", 0x18 | LC_REQ_DYLD: "LC_LOAD_WEAK_DYLIB", 0x19: "LC_SEGMENT_64",
    0x1B: "LC_UUID", 0x1C | LC_REQ_DYLD: "LC_RPATH", 0x1D: "LC_CODE_SIGNATURE",
    0x1E: "LC_SEGMENT_SPLIT_INFO", 0x1F | LC_REQ_DYLD: "LC_REEXPORT_DYLIB", 0x20: "LC_LAZY_LOAD_DYLIB",
    0x22: "LC_DYLD_INFO", 0x22 | LC_REQ_DYLD: "LC_DYLD_INFO_ONLY", 0x23 | LC_REQ_DYLD: "LC_LOAD_UPWARD_DYLIB",
    0x24: "LC_VERSION_MIN_MACOSX", 0x26: "LC_FUNCTION_STARTS", 0x28 | LC_REQ_DYLD: "LC_MAIN",
    0x29: "LC_DATA_IN_CODE", 0x2A: "LC_SOURCE_VERSION", 0x2B: "LC_DYLIB_CODE_SIGN_DRS",
    0x2C: "LC_ENCRYPTION_INFO_64", 0x2D: "LC_LINKER_OPTION", 0x32: "LC_BUILD_VERSION",
    0x33 | LC_REQ_DYLD: "LC_DYLD_EXPORTS_TRIE", 0x34 | LC_REQ_DYLD: "LC_DYLD_CHAINED_FIXUPS",
}
DYLIB_COMMANDS = {
    "LC_LOAD_DYLIB", "LC_LOAD_WEAK_DYLIB", "LC_REEXPORT_DYLIB", "LC_LAZY_LOAD_DYLIB", "LC_LOAD_UPWARD_DYLIB",
}
PLATFORMS = {1: "macos", 2: "ios", 3: "tvos", 4: "watchos", 6: "maccatalyst"}
# CodeDirectory hash types: name, hashlib name, size.
HASH_TYPES = {
    1: ("sha1", "sha1", 20), 2: ("sha256", "sha256", 32), 3: ("sha256-truncated", "sha256", 20),
    4: ("sha384", "sha384", 48),
}
CSMAGIC_EMBEDDED_SIGNATURE, CSMAGIC_CODEDIRECTORY = 0xFADE0CC0, 0xFADE0C02
CS_ADHOC, CS_LINKER_SIGNED = 0x2, 0x20000
N_STAB, N_PEXT, N_TYPE, N_EXT, N_ABS, N_SECT = 0xE0, 0x10, 0x0E, 0x01, 0x2, 0xE


def version(v):
    """X.Y.Z nibbles xxxx.yy.zz; .0 patch left off."""
    s = f"{v >> 16}.{(v >> 8) & 0xFF}"
    return s + (f".{v & 0xFF}" if v & 0xFF else "")


def cstr(data, off):
    return data[off : data.index(b"\0", off)].decode("utf-8", "replace")


def uleb(data, off):
    value = shift = 0
    while True:
        b = data[off]
        off += 1
        value |= (b & 0x7F) << shift
        shift += 7
        if b < 0x80:
            return value, off


def slices(data):
    """[(arch, offset, size, align or None)] of a thin or fat Mach-O."""
    magic = struct.unpack_from(">I", data, 0)[0]
    if magic in (FAT_MAGIC, FAT_MAGIC_64):
        n = struct.unpack_from(">I", data, 4)[0]
        out = []
        for i in range(n):
            if magic == FAT_MAGIC:
                cpu, _sub, off, size, align = struct.unpack_from(">iiIII", data, 8 + 20 * i)
            else:
                cpu, _sub, off, size, align, _ = struct.unpack_from(">iiQQII", data, 8 + 32 * i)
            if off + size > len(data):
                raise ValueError(f"fat slice {i} ({off} + {size}) is past the end of the file ({len(data)})")
            out.append((CPU_TYPES.get(cpu & 0xFFFFFFFF, f"cpu{cpu:#x}"), off, size, align))
        return out
    if struct.unpack_from("<I", data, 0)[0] != MH_MAGIC_64:
        raise ValueError("not a 64-bit Mach-O file nor a fat one")
    cpu = struct.unpack_from("<I", data, 4)[0]
    return [(CPU_TYPES.get(cpu, f"cpu{cpu:#x}"), 0, len(data), None)]


def export_trie(data, start, size):
    names = []

    def walk(node, prefix, depth):
        if depth > 256:
            raise ValueError("export trie too deep (a loop?)")
        terminal, off = uleb(data, start + node)
        if terminal:
            names.append(prefix)
        off += terminal
        count = data[off]
        off += 1
        for _ in range(count):
            end = data.index(b"\0", off)
            edge = data[off:end].decode("utf-8", "replace")
            child, off = uleb(data, end + 1)
            if child >= size:
                raise ValueError("export trie edge past its end")
            walk(child, prefix + edge, depth + 1)

    if size:
        walk(0, "", 0)
    return sorted(names)


def check_signature(data, dataoff, datasize):
    """Recomputes the CodeDirectory's hashes over the slice `data`; returns the `signature` line."""
    if dataoff + datasize > len(data):
        return "invalid: LC_CODE_SIGNATURE past the end of the slice"
    magic, _length, count = struct.unpack_from(">III", data, dataoff)
    if magic != CSMAGIC_EMBEDDED_SIGNATURE:
        return f"invalid: SuperBlob magic {magic:#x}"
    blobs = {}
    for i in range(count):
        typ, off = struct.unpack_from(">II", data, dataoff + 12 + 8 * i)
        blobs.setdefault(typ, dataoff + off)
    if 0 not in blobs:
        return "invalid: no CodeDirectory"
    cd = blobs[0]
    (magic, length, ver, flags, hash_off, ident_off, n_special, n_code, code_limit, hash_size, hash_type, _platform,
     page_shift) = struct.unpack_from(">IIIIIIIIIBBBB", data, cd)
    if magic != CSMAGIC_CODEDIRECTORY:
        return f"invalid: CodeDirectory magic {magic:#x}"
    if ver >= 0x20300:
        code_limit = struct.unpack_from(">Q", data, cd + 56)[0] or code_limit
    if hash_type not in HASH_TYPES or HASH_TYPES[hash_type][2] != hash_size:
        return f"invalid: hash type {hash_type} of size {hash_size}"
    name, algo, _ = HASH_TYPES[hash_type]
    page = 1 << page_shift if page_shift else code_limit
    if page <= 0:
        return f"invalid: page size {page} (page shift {page_shift}, code limit {code_limit})"
    if code_limit != dataoff:
        return f"invalid: the signature covers {code_limit} bytes, the code signature starts at {dataoff}"
    if n_code != (code_limit + page - 1) // page:
        return f"invalid: {n_code} code slots for {code_limit} bytes in pages of {page}"
    for i in range(n_code):
        want = data[cd + hash_off + i * hash_size : cd + hash_off + (i + 1) * hash_size]
        got = hashlib.new(algo, data[i * page : min((i + 1) * page, code_limit)]).digest()[:hash_size]
        if got != want:
            return f"invalid: page {i} (bytes {i * page}..) does not match its hash"
    special = 0
    for slot in range(1, n_special + 1):
        want = data[cd + hash_off - slot * hash_size : cd + hash_off - (slot - 1) * hash_size]
        if slot in blobs:
            blob_len = struct.unpack_from(">I", data, blobs[slot] + 4)[0]
            if hashlib.new(algo, data[blobs[slot] : blobs[slot] + blob_len]).digest()[:hash_size] != want:
                return f"invalid: special slot -{slot} does not match its blob"
            special += 1
        elif any(want):
            return f"invalid: special slot -{slot} has a hash but no blob"
    kinds = [k for bit, k in ((CS_ADHOC, "ad-hoc"), (CS_LINKER_SIGNED, "linker-signed")) if flags & bit] or ["signed"]
    extra = "" if 0x10000 not in blobs else ", CMS signature blob (not checked)"
    return (f"ok {' '.join(kinds)} ({name}, {n_code} pages of {page} bytes, {special} special slots checked, "
            f"identifier {cstr(data, cd + ident_off)}{extra})")


def read_slice(data):
    """The facts of one thin 64-bit Mach-O, as (key, value) pairs in print order."""
    magic, cpu, sub, filetype, ncmds, sizeofcmds, flags = struct.unpack_from("<IIIIIII", data, 0)
    if magic != MH_MAGIC_64:
        raise ValueError(f"slice magic {magic:#x} is not MH_MAGIC_64")
    facts = [
        ("filetype", FILETYPES.get(filetype, f"{filetype:#x}")),
        ("cpu", f"{CPU_TYPES.get(cpu, hex(cpu))} subtype {sub & 0xFFFFFF}"),
        ("flags", " ".join(n for bit, n in HEADER_FLAGS if flags & bit) or "none"),
    ]
    cmds, dylibs, trie, symtab, signature, minos = [], [], None, None, "none", None
    ident = rpaths = None
    off = 32
    if 32 + sizeofcmds > len(data):
        raise ValueError("load commands past the end of the slice")
    for _ in range(ncmds):
        cmd, size = struct.unpack_from("<II", data, off)
        if size < 8 or off + size > 32 + sizeofcmds:
            raise ValueError(f"load command {cmd:#x} at {off} has a bad size {size}")
        name = LOAD_COMMANDS.get(cmd, f"LC_{cmd:#x}")
        cmds.append(name)
        if name in DYLIB_COMMANDS or name == "LC_ID_DYLIB":
            name_off, _ts, current, compat = struct.unpack_from("<IIII", data, off + 8)
            path = cstr(data, off + name_off)
            if name == "LC_ID_DYLIB":
                ident = path
            else:
                dylibs.append(f"{path} ({name} compatibility {version(compat)} current {version(current)})")
        elif name == "LC_RPATH":
            rpaths = (rpaths or []) + [cstr(data, off + struct.unpack_from("<I", data, off + 8)[0])]
        elif name in ("LC_DYLD_INFO", "LC_DYLD_INFO_ONLY"):
            trie = struct.unpack_from("<II", data, off + 40)
        elif name == "LC_DYLD_EXPORTS_TRIE":
            trie = struct.unpack_from("<II", data, off + 8)
        elif name == "LC_SYMTAB":
            symtab = struct.unpack_from("<IIII", data, off + 8)
        elif name == "LC_CODE_SIGNATURE":
            signature = check_signature(data, *struct.unpack_from("<II", data, off + 8))
        elif name == "LC_BUILD_VERSION":
            platform, mos, sdk = struct.unpack_from("<III", data, off + 8)
            minos = f"{version(mos)} sdk {version(sdk)} (LC_BUILD_VERSION platform {PLATFORMS.get(platform, platform)})"
        elif name == "LC_VERSION_MIN_MACOSX":
            mos, sdk = struct.unpack_from("<II", data, off + 8)
            minos = f"{version(mos)} sdk {version(sdk)} (LC_VERSION_MIN_MACOSX)"
        off += size
    facts.append(("minos", minos or "unknown (no LC_BUILD_VERSION nor LC_VERSION_MIN_MACOSX)"))
    if ident is not None:
        facts.append(("id", ident))
    facts += [("dylib", d) for d in dylibs]
    facts += [("rpath", r) for r in rpaths or []]
    facts.append(("loadcmds", " ".join(cmds)))
    facts.append(("signature", signature))

    exports = export_trie(data, trie[0], trie[1]) if trie else None
    external = None
    if symtab:
        symoff, nsyms, stroff, _strsize = symtab
        external = []
        for i in range(nsyms):
            strx, ntype, _sect, _desc, _value = struct.unpack_from("<IBBHQ", data, symoff + 16 * i)
            if ntype & N_STAB or not ntype & N_EXT or ntype & N_PEXT:
                continue
            if (ntype & N_TYPE) not in (N_SECT, N_ABS):
                continue
            external.append(cstr(data, stroff + strx))
        external = sorted(set(external))
    if exports is None and external is None:
        raise ValueError("no export trie and no symbol table")
    if exports is None:
        facts.append(("exports", f"{len(external)} (symbol table; no export trie)"))
        exports = external
    elif external is None:
        facts.append(("exports", f"{len(exports)} (export trie; no symbol table)"))
    elif external == exports:
        facts.append(("exports", f"{len(exports)} (export trie; the symbol table's external defined symbols agree)"))
    else:
        only_trie, only_sym = sorted(set(exports) - set(external)), sorted(set(external) - set(exports))
        facts.append(("exports", f"{len(exports)} (export trie; the symbol table differs: only in the trie "
                      f"{' '.join(only_trie[:5]) or 'none'}, only in the symbol table {' '.join(only_sym[:5]) or 'none'})"))
    facts += [("export", e) for e in exports]
    return facts


def info(path):
    data = open(path, "rb").read()
    parts = slices(data)
    fat = struct.unpack_from(">I", data, 0)[0] in (FAT_MAGIC, FAT_MAGIC_64)
    lines = [f"file fat {len(parts)} slices" if fat else "file thin"]
    for arch, off, size, align in parts:
        lines.append(f"slice {arch} offset {off} size {size}" + (f" align 2^{align}" if align is not None else ""))
    for arch, off, size, _ in parts:
        lines += [f"{arch} {k} {v}" for k, v in read_slice(data[off : off + size])]
    return lines


def merge(out, inputs, align=14):
    """Writes the thin Mach-O files `inputs` as one fat file (FAT_MAGIC, big-endian fat_arch)."""
    thin = []
    for path in inputs:
        data = open(path, "rb").read()
        magic, cpu, sub = struct.unpack_from("<III", data, 0)
        if magic != MH_MAGIC_64:
            raise ValueError(f"{path} is not a thin 64-bit Mach-O file")
        thin.append((cpu, sub, data))
    if len({cpu for cpu, _, _ in thin}) != len(thin):
        raise ValueError("two inputs have the same CPU type")
    thin.sort(key=lambda t: (t[0] == 0x0100000C, t[0]))  # x86_64 first, arm64 last (as lipo writes them)
    header = struct.pack(">II", FAT_MAGIC, len(thin))
    body, off = [], 8 + 20 * len(thin)
    for cpu, sub, data in thin:
        start = -(-off // (1 << align)) << align
        body.append(b"\0" * (start - off) + data)
        header += struct.pack(">IIIII", cpu, sub, start, len(data), align)
        off = start + len(data)
    if off >= 1 << 32:
        raise ValueError("a fat file past 4 GiB needs FAT_MAGIC_64")
    with open(out, "wb") as f:
        f.write(header + b"".join(body))
    os.chmod(out, os.stat(inputs[0]).st_mode & 0o777)  # as the thin files (0755 from the linker)


def synthetic_dylib(cpu, names, minos, sign):
    """A small dylib of the right shape (header, load commands, symbol table, export trie and, if
    `sign`, an ad-hoc linker-signed code signature): enough for read_slice, not for dyld."""

    def node(terminal, children):  # children: [(edge, offset)]; terminal: size 2, flags 0, address 0
        head = b"\x02\x00\x00" if terminal else b"\x00"
        return head + bytes([len(children)]) + b"".join(e.encode() + b"\0" + bytes([o]) for e, o in children)

    # Export trie: root with one edge per name, leaves after it (all offsets below 128).
    leaf = node(True, [])
    root_len = len(node(False, [(n, 0) for n in names]))
    trie = node(False, [(n, root_len + i * len(leaf)) for i, n in enumerate(names)]) + leaf * len(names)
    trie += b"\0" * (-len(trie) % 8)
    strtab = b" \0" + b"".join(n.encode() + b"\0" for n in names) + b"_local\0"
    strtab += b"\0" * (-len(strtab) % 8)
    syms, strx = b"", 2
    for n in names:
        syms += struct.pack("<IBBHQ", strx, N_SECT | N_EXT, 1, 0, 0x1000)
        strx += len(n) + 1
    syms += struct.pack("<IBBHQ", strx, N_SECT | N_EXT | N_PEXT, 1, 0, 0x1000)  # hidden: not an export

    def lc_dylib(cmd, path):
        body = path.encode() + b"\0"
        body += b"\0" * (-(24 + len(body)) % 8)
        return struct.pack("<IIIIII", cmd, 24 + len(body), 24, 2, 0x10000, 0x10000) + body

    cmds = [lc_dylib(0xD, "@rpath/Test.dylib"), lc_dylib(0xC, "/usr/lib/libSystem.B.dylib"),
            struct.pack("<IIIIII", 0x32, 24, 1, minos, 0x1B0000, 0)]
    n_fixed = 3 + (1 if sign else 0)
    size_cmds = sum(map(len, cmds)) + 48 + 24 + (16 if sign else 0)
    text = 32 + size_cmds
    text += -text % 16
    code = b"\xC3" * 5000  # some bytes to sign over several pages
    trie_off = text + len(code)
    symoff = trie_off + len(trie)
    stroff = symoff + len(syms)
    sig_off = stroff + len(strtab)
    sig_off += -sig_off % 16
    cmds.append(struct.pack("<12I", 0x22 | LC_REQ_DYLD, 48, 0, 0, 0, 0, 0, 0, 0, 0, trie_off, len(trie)))
    cmds.append(struct.pack("<6I", 0x2, 24, symoff, len(names) + 1, stroff, len(strtab)))
    page = 4096
    ident = b"Test.dylib\0"
    n_code = (sig_off + page - 1) // page
    cd_len = 88 + len(ident) + 32 * n_code
    sig_len = 12 + 8 + cd_len
    if sign:
        cmds.append(struct.pack("<4I", 0x1D, 16, sig_off, sig_len))
    head = struct.pack("<8I", MH_MAGIC_64, cpu, 3 if cpu == 0x01000007 else 0, 6, n_fixed + 2, size_cmds, 0x85, 0)
    data = head + b"".join(cmds)
    data += b"\0" * (text - len(data)) + code + trie + syms + strtab
    data += b"\0" * (sig_off - len(data))
    if sign:
        pages = (data[i * page : min((i + 1) * page, sig_off)] for i in range(n_code))
        hashes = b"".join(hashlib.sha256(p).digest() for p in pages)
        cd = struct.pack(">IIIIIIIIIBBBBIIIIQQQQ", CSMAGIC_CODEDIRECTORY, cd_len, 0x20400, CS_ADHOC | CS_LINKER_SIGNED,
                         88 + len(ident), 88, 0, n_code, sig_off, 32, 2, 0, 12, 0, 0, 0, 0, 0, 0, 0, 0)
        data += struct.pack(">III", CSMAGIC_EMBEDDED_SIGNATURE, sig_len, 1) + struct.pack(">II", 0, 20) + cd + ident + hashes
    return data


def self_test():
    import tempfile

    names = ["_fmi2GetTypesPlatform", "_fmi2GetVersion", "_fmi3GetVersion"]
    with tempfile.TemporaryDirectory() as tmp:
        x86 = os.path.join(tmp, "x86_64.dylib")
        arm = os.path.join(tmp, "arm64.dylib")
        fat = os.path.join(tmp, "fat.dylib")
        open(x86, "wb").write(synthetic_dylib(0x01000007, names, 0x0A0C00, sign=False))
        open(arm, "wb").write(synthetic_dylib(0x0100000C, names, 0x0B0000, sign=True))
        merge(fat, [arm, x86])
        lines = info(fat)
        assert lines[0] == "file fat 2 slices", lines[0]
        assert lines[1].startswith("slice x86_64 offset 16384 ") and lines[1].endswith(" align 2^14"), lines[1]
        assert lines[2].startswith("slice arm64 offset 32768 "), lines[2]
        for arch in ("x86_64", "arm64"):
            mine = [line[len(arch) + 1 :] for line in lines if line.startswith(arch + " ")]
            assert "filetype MH_DYLIB" in mine, mine
            assert [m for m in mine if m.startswith("export ")] == ["export " + n for n in names], mine
            assert "exports 3 (export trie; the symbol table's external defined symbols agree)" in mine, mine
            assert "id @rpath/Test.dylib" in mine, mine
            assert any(m.startswith("dylib /usr/lib/libSystem.B.dylib (LC_LOAD_DYLIB") for m in mine), mine
        assert "x86_64 signature none" in lines, lines
        assert "x86_64 minos 10.12 sdk 27.0 (LC_BUILD_VERSION platform macos)" in lines, lines
        sig = [line for line in lines if line.startswith("arm64 signature ")][0]
        assert sig.startswith("arm64 signature ok ad-hoc linker-signed (sha256, 2 pages of 4096 bytes"), sig
        assert "arm64 minos 11.0 sdk 27.0 (LC_BUILD_VERSION platform macos)" in lines, lines
        # Each slice is the thin file byte for byte; a changed byte in the signed code fails the check.
        data = bytearray(open(fat, "rb").read())
        assert bytes(data[16384 : 16384 + os.path.getsize(x86)]) == open(x86, "rb").read()
        assert bytes(data[32768:]) == open(arm, "rb").read()
        data[32768 + 4200] ^= 1
        open(fat, "wb").write(data)
        sig = [line for line in info(fat) if line.startswith("arm64 signature ")][0]
        assert sig == "arm64 signature invalid: page 1 (bytes 4096..) does not match its hash", sig
    print("macho_info: self-test OK (merge, fat and thin reading, exports, dylibs, minos, code signature)")


def main():
    args = sys.argv[1:]
    try:
        if args == ["--self-test"]:
            self_test()
        elif len(args) >= 3 and args[0] == "--merge":
            merge(args[1], args[2:])
        elif len(args) == 1 and not args[0].startswith("--"):
            print("\n".join(info(args[0])))
        else:
            sys.exit("usage: macho_info.py FILE | --merge OUT THIN1 THIN2... | --self-test")
    except (ValueError, struct.error, IndexError, OSError) as e:
        sys.exit(f"macho_info: {e}")


if __name__ == "__main__":
    main()
