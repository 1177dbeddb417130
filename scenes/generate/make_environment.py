#!/usr/bin/env python3
"""Paints the project's environment maps: a sky over a striped ground, with a bright sun (HDR values
far above 1), as an equirectangular map (scenes/environment/sky.hdr), as six cube faces
(sky_px.hdr ... sky_nz.hdr) and as a horizontal cube cross (sky_cross.hdr), all from one function of
direction, so the three backgrounds show the same world. Standard library only; the outputs are
committed and the build never runs this. Conventions: ../shared/docs/render-model.md ("Background"), z up."""

import math
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "environment")
SUN = (0.55, -0.7, 0.45)


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def sky(d):
    """Linear RGB radiance seen along the unit direction d."""
    x, y, z = d
    if z >= 0.0:
        t = z ** 0.5
        colour = [0.85 * (1 - t) + 0.12 * t, 0.9 * (1 - t) + 0.3 * t, 1.0 * (1 - t) + 0.85 * t]
        s = normalize(SUN)
        cos_sun = x * s[0] + y * s[1] + z * s[2]
        if cos_sun > math.cos(math.radians(4.0)):
            return (30.0, 28.0, 22.0)  # the sun: HDR
        glow = max(0.0, cos_sun) ** 64
        return tuple(c + 2.0 * glow for c in colour)
    # Ground: stripes by azimuth and rings by elevation, so refraction and reflection show it.
    phi = math.atan2(y, x)
    stripe = int(math.floor((phi + math.pi) / (2 * math.pi) * 24)) % 2
    ring = int(math.floor(-z * 6)) % 2
    light = stripe ^ ring
    return (0.45, 0.38, 0.25) if light else (0.12, 0.16, 0.08)


def write_hdr(path, width, height, pixel):
    """Radiance RGBE, flat (not run-length encoded) scanlines, top row first."""
    rows = []
    for j in range(height):
        row = bytearray()
        for i in range(width):
            r, g, b = pixel(i, j)
            m = max(r, g, b)
            if m < 1e-32:
                row += b"\0\0\0\0"
                continue
            mantissa, exponent = math.frexp(m)
            scale = mantissa * 256.0 / m
            row += bytes((int(r * scale), int(g * scale), int(b * scale), exponent + 128))
        rows.append(bytes(row))
    header = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n".encode()
    with open(path, "wb") as f:
        f.write(header + b"".join(rows))


def spherical_direction(u, v):
    theta = v * math.pi
    phi = (1.0 - u) * 2.0 * math.pi - math.pi  # = atan2(y, x)
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))


def cube_direction(face, u, v):
    a, b = 2.0 * u - 1.0, 2.0 * v - 1.0
    return normalize({
        "px": (1.0, -a, -b), "nx": (-1.0, a, -b),
        "py": (a, 1.0, -b), "ny": (-a, -1.0, -b),
        "pz": (a, b, 1.0), "nz": (a, -b, -1.0),
    }[face])


def main():
    os.makedirs(OUT, exist_ok=True)
    w, h = 256, 128
    write_hdr(os.path.join(OUT, "sky.hdr"), w, h,
              lambda i, j: sky(spherical_direction((i + 0.5) / w, (j + 0.5) / h)))
    size = 48
    for face in ("px", "nx", "py", "ny", "pz", "nz"):
        write_hdr(os.path.join(OUT, f"sky_{face}.hdr"), size, size,
                  lambda i, j, f=face: sky(cube_direction(f, (i + 0.5) / size, (j + 0.5) / size)))
    cells = {(2, 1): "px", (0, 1): "nx", (1, 1): "py", (3, 1): "ny", (1, 0): "pz", (1, 2): "nz"}

    def cross(i, j):
        face = cells.get((i // size, j // size))
        if face is None:
            return (0.0, 0.0, 0.0)
        return sky(cube_direction(face, (i % size + 0.5) / size, (j % size + 0.5) / size))

    write_hdr(os.path.join(OUT, "sky_cross.hdr"), 4 * size, 3 * size, cross)
    print("wrote", sorted(os.listdir(OUT)))


if __name__ == "__main__":
    main()
