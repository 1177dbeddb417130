#!/usr/bin/env python3
"""Paints the cut-out masks of scenes/cutouts.json (MTL `map_d`; docs/render-model-decisions.md,
"Cut-out surfaces"), 8-bit grey PNGs where the surface is cut below half grey:
scenes/textures/broken_pane.png, a window pane with a hole broken through it, cracks running
from the hole; scenes/textures/fence.png, a picket fence's pointed boards with two rails.
Standard library only; the outputs are committed and the build never runs this. Row 0 is the
image's top, as a texture's v = 1 (pane.obj's uvs: u along +x, v along +z)."""

import math
import os
import struct
import zlib

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "textures")


def write_grey_png(path, width, height, value):
    """value(x, y) in [0, 1] at pixel centres, y down from the top row."""
    rows = b"".join(
        b"\x00" + bytes(max(0, min(255, round(255 * value((x + 0.5) / width, (y + 0.5) / height))))
                        for x in range(width))
        for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def broken_pane(u, v):
    """A hole with a jagged rim left of centre, and three cracks from it; 1 where glass is left."""
    cu, cv = 0.45, 0.5
    du, dv = u - cu, v - cv
    angle = math.atan2(dv, du)
    radius = 0.24 + 0.07 * math.sin(7 * angle) + 0.04 * math.sin(13 * angle + 1.0)
    if math.hypot(du, dv) < radius:
        return 0.0
    for direction, length in ((0.4, 0.45), (2.3, 0.35), (4.1, 0.4)):
        along = du * math.cos(direction) + dv * math.sin(direction)
        across = -du * math.sin(direction) + dv * math.cos(direction)
        wiggle = 0.006 * math.sin(60 * along)
        if 0 < along < length and abs(across - wiggle) < 0.008 * (1 - along / length):
            return 0.0
    return 1.0


def fence(u, v):
    """Five boards with pointed tops and two rails; 1 where wood is."""
    board = (u * 5) % 1.0
    height = v  # from the top row
    if 0.12 < board < 0.88:
        tip = 0.12 * abs(board - 0.5) / 0.38
        if height > 0.04 + tip:
            return 1.0
    if 0.25 < height < 0.32 or 0.72 < height < 0.79:
        return 1.0
    return 0.0


def main():
    os.makedirs(OUT, exist_ok=True)
    write_grey_png(os.path.join(OUT, "broken_pane.png"), 128, 128, broken_pane)
    write_grey_png(os.path.join(OUT, "fence.png"), 160, 64, fence)


if __name__ == "__main__":
    main()
