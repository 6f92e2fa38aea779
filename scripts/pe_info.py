#!/usr/bin/env python3
"""Prints a PE (Windows DLL) file's machine, exported names and imported DLLs, one per line:
`machine 0x8664`, `export NAME`, `import DLL` (standard library only; for scripts/cross-build.sh)."""

import struct
import sys


def read_pe(data: bytes):
    if data[:2] != b"MZ":
        raise ValueError("not a PE file (no MZ header)")
    pe = struct.unpack_from("<I", data, 0x3C)[0]
    if data[pe : pe + 4] != b"PE\0\0":
        raise ValueError("not a PE file (no PE signature)")
    machine, nsections = struct.unpack_from("<HH", data, pe + 4)
    opt_size = struct.unpack_from("<H", data, pe + 20)[0]
    opt = pe + 24
    magic = struct.unpack_from("<H", data, opt)[0]
    dirs = opt + (112 if magic == 0x20B else 96)
    sections = []
    for i in range(nsections):
        s = opt + opt_size + 40 * i
        vsize, va, rawsize, rawptr = struct.unpack_from("<IIII", data, s + 8)
        sections.append((va, max(vsize, rawsize), rawptr))

    def off(rva):
        for va, size, raw in sections:
            if va <= rva < va + size:
                return rva - va + raw
        raise ValueError(f"RVA {rva:#x} outside every section")

    def cstr(rva):
        o = off(rva)
        return data[o : data.index(b"\0", o)].decode("ascii", "replace")

    exports, imports = [], []
    exp_rva, exp_size = struct.unpack_from("<II", data, dirs)
    if exp_rva:
        e = off(exp_rva)
        n_names = struct.unpack_from("<I", data, e + 24)[0]
        names_rva = struct.unpack_from("<I", data, e + 32)[0]
        for i in range(n_names):
            exports.append(cstr(struct.unpack_from("<I", data, off(names_rva) + 4 * i)[0]))
    # The DLL names of the import directory (entry 1: descriptors of 20 bytes, the name's RVA at
    # +12) and of the delay-load directory (entry 13: 32 bytes, the name at +4); a zero name ends each.
    for entry, size, name_at in ((1, 20, 12), (13, 32, 4)):
        rva = struct.unpack_from("<I", data, dirs + entry * 8)[0]
        d = off(rva) if rva else None
        while d is not None:
            name_rva = struct.unpack_from("<I", data, d + name_at)[0]
            if name_rva == 0:
                break
            imports.append(cstr(name_rva))
            d += size
    return machine, exports, imports


def main():
    machine, exports, imports = read_pe(open(sys.argv[1], "rb").read())
    print(f"machine {machine:#x}")
    for name in exports:
        print(f"export {name}")
    for name in imports:
        print(f"import {name}")


if __name__ == "__main__":
    main()
