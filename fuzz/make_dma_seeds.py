#!/usr/bin/env python3
"""Writes the seed inputs of fuzz/corpus/dma_descriptors: the layout
fuzz_dma_descriptors.cpp's header describes (an 8-byte header, the register
descriptor, the memory image). Run from anywhere:
python3 fuzz/make_dma_seeds.py.
"""
import pathlib
import struct

CORPUS = pathlib.Path(__file__).resolve().parent / "corpus" / "dma_descriptors"


def desc(ctrl, src, dst, length, src_stride=0, dst_stride=0, next_address=0, mask=0):
    """One descriptor's 8 little-endian words (contract/dma/dma_descriptor.h)."""
    return struct.pack("<8I", ctrl, src, dst, length, src_stride, dst_stride, next_address, mask)


def header(lanes, cmem, base, buffer, chain_only):
    """Indices into the target's tables: lanes {0, 1, 8, 24, 96}, CMEM
    {16, 64, 4096}, base {0, 0x1000, 0xFFFFF000}, buffer 16 << n."""
    return bytes([lanes, cmem, base, buffer, chain_only, 0, 0, 0])


def main():
    CORPUS.mkdir(parents=True, exist_ok=True)
    memory = bytearray(1024)
    for i in range(256, 1024):
        memory[i] = (i * 7) & 0xFF
    seeds = {}
    # An overlapping register copy, then a chain: a reshuffle of 2-byte
    # values into 96 CUs and a masked broadcast.
    chain = bytearray(memory)
    chain[0x40:0x60] = desc(0x20, 0x200, 0, 2 * 96, next_address=0x80)
    chain[0x80:0xA0] = desc(0x13, 0x300, 4, 21, dst_stride=2, mask=0x3F0)
    chain[0x3F0:0x3FC] = b"\xff\x0f" * 6
    seeds["seed-chain.bin"] = header(4, 2, 0, 2, 0) + desc(0x12, 0x100, 0x104, 600, next_address=0x40) + chain
    # A chain only, whose second descriptor points back to the first (base 0x1000).
    loop = bytearray(memory)
    loop[0:32] = desc(0x12, 0x1100, 0x1200, 8, next_address=0x1020)
    loop[0x20:0x40] = desc(0x12, 0x1100, 0x1200, 8, next_address=0x1000)
    seeds["seed-loop.bin"] = header(2, 1, 1, 0, 1) + desc(0, 0, 0, 0, next_address=0x1000) + loop
    # A CMEM read out to a range past the top of the address space (base 0xFFFFF000).
    seeds["seed-top.bin"] = header(2, 1, 2, 1, 0) + desc(0x11, 0, 0xFFFFFFF0, 16) + bytes(memory[:256])
    # Reserved bits, and a mask on a copy: refused.
    seeds["seed-reserved.bin"] = header(3, 2, 0, 3, 0) + desc(0x112, 0, 0x100, 64, mask=4) + bytes(memory[:512])
    for old in CORPUS.glob("seed-*"):
        old.unlink()
    for name, data in seeds.items():
        (CORPUS / name).write_bytes(data)
        print(f"dma_descriptors/{name}: {len(data)} bytes")


if __name__ == "__main__":
    main()
