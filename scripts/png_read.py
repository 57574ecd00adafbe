"""Reads the PNG files soc_sim writes (8-bit RGB or RGBA, not interlaced), with the standard library alone.

For the checks that look at a frame's pixels without Pillow or numpy (they run
under the system's Python): scripts/check_add_backend.py and
tests/host/iss/soc_sim_gdb_session.py.

    width, height, channels, rows = png_read.read_png(path)   # rows: bytes, channels per pixel

Raises ValueError naming the file when it is not such a PNG.
"""

import pathlib
import struct
import zlib

SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {2: 3, 6: 4}  # PNG colour type: RGB, RGBA


def _unfilter(kind, line, previous, channels):
    """Undoes one row's filter (PNG specification, section 9) in place."""
    for i in range(len(line)):
        left = line[i - channels] if i >= channels else 0
        up = previous[i]
        up_left = previous[i - channels] if i >= channels else 0
        if kind == 1:
            line[i] = (line[i] + left) & 255
        elif kind == 2:
            line[i] = (line[i] + up) & 255
        elif kind == 3:
            line[i] = (line[i] + (left + up) // 2) & 255
        elif kind == 4:
            p = left + up - up_left
            pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
            line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else up_left)) & 255


def read_png(path):
    """(width, height, channels, rows): each row the bytes of its pixels, `channels` (3 or 4) a pixel."""
    path = pathlib.Path(path)
    data = path.read_bytes()
    if data[:8] != SIGNATURE:
        raise ValueError(f"{path}: not a PNG file")
    position, header, idat = 8, None, b""
    while position + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[position : position + 8])
        body = data[position + 8 : position + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        position += 12 + length
    if header is None or header[2] != 8 or header[3] not in CHANNELS or header[6] != 0:
        raise ValueError(f"{path}: not an 8-bit, non-interlaced RGB or RGBA PNG (IHDR {header})")
    width, height, channels = header[0], header[1], CHANNELS[header[3]]
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        line = bytearray(raw[start + 1 : start + 1 + stride])
        _unfilter(raw[start], line, previous, channels)
        rows.append(bytes(line))
        previous = line
    return width, height, channels, rows
