#!/usr/bin/env python3
"""Generates the images lab 3's scenes use: scenes/textures/*.png (8-bit sRGB RGBA).

Python 3 standard library only, deterministic (same bytes on every run). The images are made
from scratch here, so they carry no third-party rights: this script and its output are
released under CC0 1.0 (public domain dedication), like scripts/make_model.py's pawn.

    python3 scripts/make_textures.py            # writes scenes/textures/
    python3 scripts/make_textures.py OUT_DIR

  * tiles.png  (256 x 256): stone floor tiles, 4 x 4 per image, mortar lines and speckle:
    fine detail for mipmaps and anisotropy on a grazing floor (tiled with uv_scale).
  * bricks.png (256 x 128): red bricks in running bond, a non-square image.
  * wood.png   (100 x 60):  wood grain, a non-power-of-two size (its mip chain has odd sizes).
"""
import math
import os
import struct
import sys
import zlib


def png(path, width, height, pixel):
    """Writes width x height RGBA from pixel(x, y) -> (r, g, b) in 0..255."""
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # filter: none
        for x in range(width):
            r, g, b = pixel(x, y)
            rows += bytes((max(0, min(255, int(r))), max(0, min(255, int(g))), max(0, min(255, int(b))), 255))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def noise(x, y, seed):
    """A repeatable hash in [0, 1)."""
    h = (x * 374761393 + y * 668265263 + seed * 982451653) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65536.0


def tiles(x, y):
    tx, ty = x // 64, y // 64  # which tile
    lx, ly = x % 64, y % 64
    if lx < 3 or ly < 3:  # mortar
        return (60, 58, 55)
    base = 150 + 60 * noise(tx, ty, 1)  # each tile its own shade
    speck = 40 * (noise(x, y, 2) - 0.5)
    warm = 12 * noise(tx, ty, 3)
    return (base + speck + warm, base + speck, base + speck - warm)


def bricks(x, y):
    row = y // 32
    shift = 32 if row % 2 else 0
    bx = (x + shift) // 64
    lx, ly = (x + shift) % 64, y % 32
    if lx < 3 or ly < 3:
        return (200, 195, 185)
    shade = 0.8 + 0.3 * noise(bx, row, 4) + 0.15 * (noise(x, y, 5) - 0.5)
    return (170 * shade, 60 * shade, 45 * shade)


def wood(x, y):
    ring = math.sin(0.25 * x + 3.0 * math.sin(0.05 * y) + 0.8 * noise(x // 7, y // 11, 6))
    t = 0.5 + 0.5 * ring
    return (120 + 70 * t, 75 + 45 * t, 35 + 20 * t)


def main():
    if sys.argv[1:2] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return
    if len(sys.argv) > 2 or sys.argv[1:2] and sys.argv[1].startswith("-"):
        sys.exit("make_textures: usage: python3 scripts/make_textures.py [OUT_DIR] (see --help)")
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "textures")
    os.makedirs(out, exist_ok=True)
    png(os.path.join(out, "tiles.png"), 256, 256, tiles)
    png(os.path.join(out, "bricks.png"), 256, 128, bricks)
    png(os.path.join(out, "wood.png"), 100, 60, wood)
    print("wrote", os.path.normpath(out))


if __name__ == "__main__":
    main()
