#!/usr/bin/env python3
"""A firmware ELF's flash and RAM, read from its section headers.

Flash: every allocated section with contents (vector table, code, read-only data with the
network, and the initial image of .data). RAM: every allocated section in the RAM window from
0x20000000 (.data, .bss, .uninit); the stack takes the rest from the top down.

    scripts/elf_sizes.py ELF [FLASH_BYTES [RAM_BYTES]]   (default: the STM32F405's 1 MiB, 128 KiB)

Fails when `.data` exceeds DATA_LIMIT bytes: the planner and its storage are `static`s that
must start as all-zero bytes, so that they land in `.bss` instead of also costing their size
in flash for the initial image of `.data`.

Used by scripts/test.sh (its firmware size steps) and scripts/onboard-figures.sh.
"""
import struct
import sys

SHF_ALLOC, SHT_NOBITS = 0x2, 8
DATA_LIMIT = 4096


def sections(path):
    """(name, address, size, has contents) of each allocated, non-empty section."""
    data = open(path, "rb").read()
    assert data[:4] == b"\x7fELF" and data[4] == 1, "expected a 32-bit ELF"
    shoff, = struct.unpack_from("<I", data, 0x20)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x2E)

    def sh(i):
        return struct.unpack_from("<IIIIIIIIII", data, shoff + i * shentsize)

    strtab_off = sh(shstrndx)[4]
    out = []
    for i in range(shnum):
        n, typ, flags, addr, _off, size = sh(i)[:6]
        if not flags & SHF_ALLOC or size == 0:
            continue
        name = data[strtab_off + n:data.index(b"\0", strtab_off + n)].decode()
        out.append((name, addr, size, typ != SHT_NOBITS))
    return out


def sizes(path, ram_size):
    """(flash bytes, RAM bytes, sections) of the ELF at `path`."""
    rows = sections(path)
    flash = sum(size for _, _, size, stored in rows if stored)
    ram = sum(size for _, addr, size, _ in rows if 0x20000000 <= addr < 0x20000000 + ram_size)
    return flash, ram, rows


def main():
    path = sys.argv[1]
    flash_size = int(sys.argv[2]) if len(sys.argv) > 2 else 1048576
    ram_size = int(sys.argv[3]) if len(sys.argv) > 3 else 131072
    flash, ram, rows = sizes(path, ram_size)
    for name, addr, size, _ in rows:
        print(f"  {name:<16} 0x{addr:08x} {size:>9} B")
    print(f"flash: {flash} B of {flash_size} ({100 * flash / flash_size:.1f} %)")
    print(f"RAM:   {ram} B of {ram_size} ({100 * ram / ram_size:.1f} %) static; the stack has the rest")
    data = sum(size for name, _, size, _ in rows if name == ".data")
    if data > DATA_LIMIT:
        print(f"FAILED: .data is {data} B (at most {DATA_LIMIT}): a static planner or storage is not all-zero bytes")
        sys.exit(1)


if __name__ == "__main__":
    main()
