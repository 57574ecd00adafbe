#!/usr/bin/env python3
"""Writes the binary seed inputs of fuzz/corpus (raster_commands, gl, elf,
gdb_packets, semihosting), and
the regression inputs written for a fault rather than kept as found.

The text seeds (config, obj, array_asm) are written by hand. Run from
anywhere: python3 fuzz/make_seeds.py. The layouts are those the targets'
headers describe (fuzz_raster_commands.cpp, fuzz_gl.cpp, fuzz_elf.cpp,
fuzz_gdb_packets.cpp, fuzz_semihosting.cpp).
"""

import pathlib
import struct

CORPUS = pathlib.Path(__file__).resolve().parent / "corpus"


def words(*values):
    return b"".join(struct.pack("<I", v & 0xFFFFFFFF) for v in values)


# --- raster_commands: a 15-byte header, then the memory image at address 0.
def raster_header(flags, width, height, tile_w, tile_h, color_base, depth_base):
    return struct.pack("<BHHBBII", flags, width - 1, height - 1, tile_w - 1, tile_h - 1, color_base, depth_base)


def vertex(x, y, rgba=0xFFFFFFFF, z=0, s=0.0, t=0.0, w=1.0):
    return words(int(x * 16) | int(y * 16) << 16, z, rgba) + struct.pack("<fff", s / w, t / w, 1 / w)


def raster_frame(
    flags, width, height, tile_w, tile_h, state_flags, triangles, texture=None, texture_mode=1 << 2 | 1 << 4
):
    tiles = ((width + tile_w - 1) // tile_w) * ((height + tile_h - 1) // tile_h)
    LIST, STATE, TRIS, TEX = 0x80, 0xC0, 0x100, 0x200
    assert tiles <= 16
    commands = words(1 | 7 << 8, 0xFF202020, 0xFFFFFF, 0 | 15 << 8 | 1 << 12 | 0xFF << 16, 2, STATE)
    for i in range(len(triangles)):
        commands += words(3, TRIS + 72 * i)
    count = len(commands) // 4
    image = bytearray(TEX if texture is None else TEX + len(texture))
    image[0 : 8 * tiles] = words(*([LIST, count] * tiles))
    image[LIST : LIST + len(commands)] = commands
    tex_size = 0
    if texture is not None:
        tex_size = 2 | 2 << 8  # 4x4
        image[TEX : TEX + len(texture)] = texture
    state = words(
        state_flags, 1, 7, 7 | 0xFF << 16 | 0xFF << 24, 0, 1 | 0 << 8 | 3 << 16, 15, 0, 0, TEX, tex_size, texture_mode
    )
    image[STATE : STATE + 48] = state
    for i, tri in enumerate(triangles):
        image[TRIS + 72 * i : TRIS + 72 * (i + 1)] = b"".join(tri)
    return raster_header(flags, width, height, tile_w, tile_h, 0x10000, 0x30000) + bytes(image)


def textured_frame(triangle, texture_mode=1 << 2 | 1 << 4):
    """One triangle on a 32 x 32 screen in one tile, textured (the 4x4 texture of bytes 0..63) and flat shaded."""
    return raster_frame(
        0, 32, 32, 32, 32, 1 << 7 | 1 << 8, [triangle], texture=bytes(range(64)), texture_mode=texture_mode
    )


# --- gl: one byte per entry point (the case of fuzz_gl.cpp's switch), then its arguments.
def gl_stream(*calls):
    return b"".join(calls)


ENABLE_VERTEX_ARRAY = bytes([145, 0])  # glEnableClientState(GL_VERTEX_ARRAY)
ENABLE_TEXCOORD_ARRAY = bytes([145, 2])  # glEnableClientState(GL_TEXTURE_COORD_ARRAY)
VERTEX_POINTER_FLOAT3 = bytes([147, 1, 1, 1]) + struct.pack("<H", 64)  # glVertexPointer(3, GL_FLOAT, 0, client + 64)
DRAW_TRIANGLES_6 = bytes([149, 1]) + struct.pack("<H", 6)  # glDrawArrays(GL_TRIANGLES, 0, 6)
GET_ERROR = bytes([54])
TEX_IMAGE_4x4 = bytes([132, 1, 1]) + struct.pack("<H", 0) + bytes([1, 1, 2, 1, 2, 1, 1, 1, 1]) + struct.pack("<H", 256)
ENABLE_TEXTURE = bytes([146, 1])  # glEnable(GL_TEXTURE_2D)
ORTHO_EDGES = bytes([100] + [1, 0, 1, 1, 1, 2, 1, 3, 1, 4, 1, 12])  # glOrthof over edge floats
PUSH_POP = bytes([112, 112, 111, 111, 111])  # one pop too many: GL_STACK_UNDERFLOW


def gl_enum(value):  # Arguments::e(), any 32-bit value
    return bytes([0]) + struct.pack("<I", value)


def gl_int_edge(index):  # Arguments::i(), EDGES[index]: 0 is 0, 17 is INT_MAX
    return bytes([1, index])


GL_TEXTURE_2D, GL_RGBA = 0x0DE1, 0x1908
# glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 0, 0, INT_MAX, INT_MAX, 0) and
# glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, INT_MAX, INT_MAX): they
# allocated width x height x 4 bytes before checking the size.
COPY_TEX_HUGE = (
    bytes([24])
    + gl_enum(GL_TEXTURE_2D)
    + gl_int_edge(0)
    + gl_enum(GL_RGBA)
    + gl_int_edge(0) * 2
    + gl_int_edge(17) * 2
    + gl_int_edge(0)
    + bytes([25])
    + gl_enum(GL_TEXTURE_2D)
    + gl_int_edge(0) * 5
    + gl_int_edge(17) * 2
    + GET_ERROR
)


# --- elf: an ARM executable. Segments are (address, file bytes, memory
# bytes, flags); the file bytes of every segment follow the headers, in turn.
def elf(segments, entry=None):
    headers = 52 + 32 * len(segments)
    out = bytearray(b"\x7fELF\x01\x01\x01" + bytes(9))
    out += struct.pack(
        "<HHIIIIIHHHHHH",
        2,
        40,
        1,
        segments[0][0] if entry is None else entry,
        52,
        0,
        0,
        52,
        32,
        len(segments),
        40,
        0,
        0,
    )
    offset = headers
    for address, data, memory_bytes, flags in segments:
        out += struct.pack("<IIIIIIII", 1, offset, address, address, len(data), memory_bytes, flags, 4)
        offset += len(data)
    for _, data, _, _ in segments:
        out += data
    return bytes(out)


EXIT_PROGRAM = words(0xE3A00005, 0xE3A0124F, 0xE5810000, 0xEAFFFFFE)  # mov r0,#5; ldr r1,=EXIT; str r0,[r1]; b .
HANG_PROGRAM = words(0xE321F0D3, 0xEAFFFFFE)  # msr cpsr_c, #0xd3; b .


# --- gdb_packets: what a client sends, each packet framed with its checksum.
def gdb(*packets, ack=True):
    out = b""
    for p in packets:
        out += b"$" + p + b"#" + b"%02x" % (sum(p) & 0xFF) + (b"+" if ack else b"")
    return out


# --- semihosting: a 1,024-byte memory image, then calls of (operation, parameter).
def semihosting(image, *calls):
    memory = bytearray(1024)
    for address, data in image:
        memory[address : address + len(data)] = data
    return bytes(memory) + b"".join(struct.pack("<BI", op, parameter) for op, parameter in calls)


def main():
    (CORPUS / "raster_commands").mkdir(parents=True, exist_ok=True)
    for target in ("gl", "elf", "gdb_packets", "semihosting"):
        (CORPUS / target).mkdir(parents=True, exist_ok=True)
    operation = {
        "open": 0,
        "close": 1,
        "writec": 2,
        "write0": 3,
        "write": 4,
        "read": 5,
        "flen": 9,
        "get_cmdline": 13,
        "exit_extended": 15,
    }  # indices into semihosting.def's list
    depth = 1 | 2
    tri = [vertex(2, 2, 0xFF0000FF, 100), vertex(60, 4, 0xFF00FF00, 200), vertex(30, 30, 0xFFFF0000, 300)]
    seeds = {
        "raster_commands/seed-clear-triangle.bin": raster_frame(0, 64, 32, 32, 16, depth, [tri]),
        "raster_commands/seed-rgba-smooth-blend.bin": raster_frame(
            1 | 2, 48, 40, 16, 8, depth | 1 << 4 | 1 << 9, [tri, list(reversed(tri))]
        ),
        "raster_commands/seed-textured.bin": textured_frame(
            [vertex(0, 0, s=0, t=0), vertex(31, 0, s=1, t=0, w=2.0), vertex(0, 31, s=0, t=1)]
        ),
        # Mirrored (s falls along x) and minified with MIN LINEAR, MAG NEAREST: the footprint's
        # differences are negative (a fuzzer's find: a left shift of a negative value).
        "raster_commands/regress-mirrored-minified.bin": textured_frame(
            [vertex(0, 0, s=8, t=0), vertex(31, 0, s=0, t=0, w=2.0), vertex(0, 31, s=8, t=8)],
            texture_mode=1 | 1 << 2 | 1 << 4,
        ),
        "gl/seed-triangles.bin": gl_stream(ENABLE_VERTEX_ARRAY, VERTEX_POINTER_FLOAT3, DRAW_TRIANGLES_6, GET_ERROR),
        "gl/seed-textured.bin": gl_stream(
            TEX_IMAGE_4x4,
            ENABLE_TEXTURE,
            ENABLE_VERTEX_ARRAY,
            ENABLE_TEXCOORD_ARRAY,
            VERTEX_POINTER_FLOAT3,
            DRAW_TRIANGLES_6,
            GET_ERROR,
        ),
        "gl/seed-matrices.bin": gl_stream(
            ORTHO_EDGES, PUSH_POP, GET_ERROR, ENABLE_VERTEX_ARRAY, VERTEX_POINTER_FLOAT3, DRAW_TRIANGLES_6
        ),
        "gl/regress-copy-tex-image-huge-size.bin": COPY_TEX_HUGE,
        "elf/seed-exit.elf": elf([(0x8000, EXIT_PROGRAM, 16, 5)]),
        "elf/seed-two-segments.elf": elf([(0x100, HANG_PROGRAM, 8, 5), (0x2000, words(1, 2, 3), 0x100, 6)]),
        "elf/seed-overlapping.elf": elf([(0x100, EXIT_PROGRAM, 16, 5), (0x108, words(7), 4, 6)]),
        "elf/seed-large-bss.elf": elf([(0, EXIT_PROGRAM, 16, 5), (0x10000, b"", 0x2000000, 6)]),
        "gdb_packets/seed-session.bin": b"+"
        + gdb(
            b"qSupported:multiprocess+;swbreak+",
            b"?",
            b"g",
            b"qXfer:features:read:target.xml:0,ffb",
            b"m0,40",
            b"M100,4:01020304",
            b"p10",
            b"P3=78563412",
            b"Z0,100,4",
            b"z0,100,4",
            b"G" + b"00000000" * 16 + b"d3000000",
            b"s",
            b"c",
            b"D",
        ),
        "gdb_packets/seed-errors.bin": gdb(b"G" + b"zz" * 68, b"M100,2:0g", b"m,", b"P=1", b"qXfer:x")
        + b"$m0,4#00-\x03$g#6"
        + b"$"
        + b"a" * 100,
        "semihosting/seed-console.bin": semihosting(
            [
                (0x100, b":tt"),
                (0x200, words(0x100, 4, 3)),
                (0x210, words(1, 0x300, 200)),
                (0x300, b"hello\n" * 40),
                (0x40, b"text\0"),
            ],
            (operation["open"], 0x200),
            (operation["write"], 0x210),
            (operation["write0"], 0x40),
            (operation["writec"], 0x300),
            (operation["exit_extended"], 0x3F8),
        ),
        "semihosting/seed-files.bin": semihosting(
            [
                (0x100, b":fuzz/file"),
                (0x120, b":fuzz/sink"),
                (0x200, words(0x100, 0, 10)),
                (0x210, words(0x120, 4, 10)),
                (0x220, words(1, 0x300, 100)),
                (0x230, words(2, 0x300, 100)),
                (0x240, words(1)),
                (0x250, words(0x380, 64)),
            ],
            (operation["open"], 0x200),
            (operation["open"], 0x210),
            (operation["read"], 0x220),
            (operation["write"], 0x230),
            (operation["flen"], 0x240),
            (operation["get_cmdline"], 0x250),
            (operation["close"], 0x240),
        ),
    }
    for name, data in seeds.items():
        (CORPUS / name).write_bytes(data)
        print(f"{name}: {len(data)} bytes")


if __name__ == "__main__":
    main()
