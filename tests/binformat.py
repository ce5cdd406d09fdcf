"""What a shared library is, read from its bytes: format, architecture,
exported symbols and (ELF) the glibc symbol versions it needs.  Independent of
the build: the tests check the cross-built binaries with it."""
from __future__ import annotations

import struct
from dataclasses import dataclass, field


@dataclass
class Binary:
    format: str                      # "ELF", "PE", "Mach-O"
    arch: str                        # "x86_64" or "aarch64"
    exports: set = field(default_factory=set)
    glibc_needed: list = field(default_factory=list)  # e.g. ["2.2.5", "2.14"]
    install_name: str | None = None  # Mach-O: the library's own name (LC_ID_DYLIB)


def read(data: bytes) -> Binary:
    if data[:4] == b"\x7fELF":
        return _elf(data)
    if data[:2] == b"MZ":
        return _pe(data)
    if data[:4] in (b"\xcf\xfa\xed\xfe",):
        return _macho(data)
    raise ValueError("not an ELF, PE or 64-bit Mach-O file")


def _cstr(data: bytes, off: int) -> str:
    return data[off:data.index(b"\0", off)].decode()


def _elf(d: bytes) -> Binary:
    assert d[4] == 2 and d[5] == 1, "64-bit little-endian ELF expected"
    machine = struct.unpack_from("<H", d, 18)[0]
    arch = {62: "x86_64", 183: "aarch64"}[machine]
    shoff, = struct.unpack_from("<Q", d, 40)
    shentsize, shnum = struct.unpack_from("<HH", d, 58)
    secs = [struct.unpack_from("<IIQQQQIIQQ", d, shoff + i * shentsize) for i in range(shnum)]
    # (name, type, flags, addr, offset, size, link, info, align, entsize)
    out = Binary("ELF", arch)
    for s in secs:
        if s[1] == 11:  # SHT_DYNSYM
            strtab = secs[s[6]]
            for k in range(s[5] // 24):
                name_off, info, other, shndx = struct.unpack_from("<IBBH", d, s[4] + 24 * k)
                bind, vis = info >> 4, other & 3
                if shndx != 0 and bind in (1, 2) and vis == 0:  # defined, global/weak, default
                    out.exports.add(_cstr(d, strtab[4] + name_off))
        if s[1] == 0x6ffffffe:  # SHT_GNU_verneed
            strtab = secs[s[6]]
            off = s[4]
            for _ in range(s[7]):
                _, cnt, _, aux, nxt = struct.unpack_from("<HHIII", d, off)
                a = off + aux
                for _ in range(cnt):
                    _, _, _, name, anext = struct.unpack_from("<IHHII", d, a)
                    ver = _cstr(d, strtab[4] + name)
                    if ver.startswith("GLIBC_"):
                        out.glibc_needed.append(ver[6:])
                    a += anext
                off += nxt
    return out


def _pe(d: bytes) -> Binary:
    pe, = struct.unpack_from("<I", d, 0x3C)
    assert d[pe:pe + 4] == b"PE\0\0"
    machine, nsec, _, _, _, opt_size, _ = struct.unpack_from("<HHIIIHH", d, pe + 4)
    arch = {0x8664: "x86_64", 0xAA64: "aarch64"}[machine]
    opt = pe + 24
    assert struct.unpack_from("<H", d, opt)[0] == 0x20B, "PE32+ expected"
    export_rva, _ = struct.unpack_from("<II", d, opt + 112)
    sections = [struct.unpack_from("<8sIIII", d, opt + opt_size + 40 * i) for i in range(nsec)]

    def off(rva):
        for _, vsize, vaddr, rsize, raw in sections:
            if vaddr <= rva < vaddr + max(vsize, rsize):
                return rva - vaddr + raw
        raise ValueError(rva)
    out = Binary("PE", arch)
    if export_rva:
        e = off(export_rva)
        n_names, = struct.unpack_from("<I", d, e + 24)
        names_rva, = struct.unpack_from("<I", d, e + 32)
        for k in range(n_names):
            rva, = struct.unpack_from("<I", d, off(names_rva) + 4 * k)
            out.exports.add(_cstr(d, off(rva)))
    return out


def _macho(d: bytes) -> Binary:
    cputype, _, filetype, ncmds, _, _ = struct.unpack_from("<iiIIII", d, 4)
    arch = {0x01000007: "x86_64", 0x0100000C: "aarch64"}[cputype]
    assert filetype == 6, "MH_DYLIB expected"
    out = Binary("Mach-O", arch)
    off = 32
    for _ in range(ncmds):
        cmd, size = struct.unpack_from("<II", d, off)
        if cmd == 0xD:  # LC_ID_DYLIB: the name offset, then timestamp and versions
            name_off, = struct.unpack_from("<I", d, off + 8)
            out.install_name = _cstr(d, off + name_off)
        if cmd == 2:  # LC_SYMTAB
            symoff, nsyms, stroff, _ = struct.unpack_from("<IIII", d, off + 8)
            for k in range(nsyms):
                strx, ntype, nsect, _, _ = struct.unpack_from("<IBBHQ", d, symoff + 16 * k)
                if ntype & 0x01 and (ntype & 0x0E) == 0x0E and not ntype & 0x10:  # N_EXT, N_SECT, not private
                    name = _cstr(d, stroff + strx)
                    out.exports.add(name[1:] if name.startswith("_") else name)
        off += size
    return out
