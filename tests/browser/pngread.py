"""A minimal PNG reader for screenshot checks (8-bit RGB/RGBA, non-interlaced, as Chromium writes).

Kept in the tests so the suite needs no imaging library.
"""

from __future__ import annotations

import struct
import zlib

import numpy as np


def read_png(data: bytes) -> np.ndarray:
    """Decode to an array of shape (height, width, channels), dtype uint8."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"unsupported PNG (depth {depth}, colour type {colour}, interlace {interlace})")
    channels = 3 if colour == 2 else 4
    rows = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height,
                                                                         width * channels + 1)
    filters = rows[:, 0].astype(np.int32)
    if np.any(filters > 4):
        raise ValueError(f"unknown PNG filter type {filters.max()}")
    line = rows[:, 1:].reshape(height, width, channels).astype(np.int32)
    # The image with a row and a column of zeros before it (what the filters read outside it).
    # A pixel is predicted from its left (a), upper (b) and upper-left (c) neighbours, so the
    # pixels of one anti-diagonal (y + x constant) are decoded together, one diagonal after the
    # other: h + w - 1 steps instead of a step per byte of the rows filtered by Sub, Average or
    # Paeth (most of a screenshot's).
    out = np.zeros((height + 1, width + 1, channels), dtype=np.int32)
    for d in range(height + width - 1):
        y = np.arange(max(0, d - width + 1), min(height - 1, d) + 1)
        x = d - y
        a, b, c = out[y + 1, x], out[y, x + 1], out[y, x]
        f = filters[y][:, None]
        p = a + b - c
        pa, pb, pc = np.abs(p - a), np.abs(p - b), np.abs(p - c)
        paeth = np.where((pa <= pb) & (pa <= pc), a, np.where(pb <= pc, b, c))
        pred = np.select([f == 0, f == 1, f == 2, f == 3], [0, a, b, (a + b) // 2], paeth)
        out[y + 1, x + 1] = (line[y, x] + pred) & 255
    return out[1:, 1:].astype(np.uint8)
