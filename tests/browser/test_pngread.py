"""The screenshot checks' PNG reader (pngread.py) against images of known pixels, written with
every one of PNG's five row filters (None, Sub, Up, Average, Paeth) in RGB and RGBA."""

from __future__ import annotations

import struct
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from pngread import read_png  # noqa: E402


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def write_png(img: np.ndarray, filters: np.ndarray) -> bytes:
    """``img`` (h, w, 3 or 4) uint8 as a PNG whose row y is filtered by ``filters[y]``."""
    h, w, ch = img.shape
    x = np.zeros((h + 1, w + 1, ch), dtype=np.int32)  # zeros outside the image, as decoders read
    x[1:, 1:] = img
    a, b, c = x[1:, :-1], x[:-1, 1:], x[:-1, :-1]  # left, up, upper left of every pixel
    p = a + b - c
    pa, pb, pc = np.abs(p - a), np.abs(p - b), np.abs(p - c)
    paeth = np.where((pa <= pb) & (pa <= pc), a, np.where(pb <= pc, b, c))
    f = filters[:, None, None]
    pred = np.select([f == 0, f == 1, f == 2, f == 3], [0, a, b, (a + b) // 2], paeth)
    rows = ((img.astype(np.int32) - pred) & 255).astype(np.uint8).reshape(h, w * ch)
    raw = np.concatenate([filters.astype(np.uint8)[:, None], rows], axis=1).tobytes()
    header = struct.pack(">IIBBBBB", w, h, 8, 2 if ch == 3 else 6, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(raw))
            + _chunk(b"IEND", b""))


@pytest.mark.parametrize("channels", [3, 4])
def test_every_filter_decodes_to_the_pixels_written(channels):
    rng = np.random.default_rng(7)
    h, w = 40, 23
    img = rng.integers(0, 256, (h, w, channels), dtype=np.uint8)
    img[10:20] = img[10:20] // 64 * 64  # flat runs too, where the predictors tie
    filters = np.arange(h) % 5  # each filter after each other one
    rng.shuffle(filters[5:])
    assert np.array_equal(read_png(write_png(img, filters)), img)
