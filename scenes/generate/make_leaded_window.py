#!/usr/bin/env python3
"""Writes scenes/meshes/leaded_window.gltf for scenes/leaded_window.json: a leaded window of thin
glass (glTF's KHR_materials_transmission without a volume) whose transmissionTexture says which
parts are glass (docs/render-model-decisions.md, "Transmission textures"): diamond quarries of
tinted glass, their colours in the base colour texture, held by lead came, where the transmission
texture is 0 and the material is its opaque model, a dull dark dielectric. The images and the
buffer are embedded as data URIs. Standard library only; the output is committed and the build
never runs this. glTF is +Y up: vitrum places (x, y, z) at (x, -z, y)."""

import math
import os

from gltf_square import data_uri, png, write_square_gltf

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "meshes", "leaded_window.gltf")
SIZE = 256
DIAMONDS = 4        # quarries across the window
CAME = 0.012        # half the came's width, in texture coordinates
FRAME = 0.03        # the came around the edge
LEAD = (0.16, 0.16, 0.17)
# sRGB colours of the quarries' glass: amber, blue, green, rose and clear.
GLASS = [(1.0, 0.75, 0.35), (0.45, 0.65, 1.0), (0.55, 0.9, 0.55), (1.0, 0.55, 0.6), (0.97, 0.97, 0.97)]


def quarry(u, v):
    """The diamond (a, b) that (u, v) lies in, and whether it lies on the came instead."""
    s, d = (u + v) * DIAMONDS, (u - v) * DIAMONDS
    on_came = min(s - math.floor(s), math.ceil(s) - s) < CAME * DIAMONDS * math.sqrt(2) or \
        min(d - math.floor(d), math.ceil(d) - d) < CAME * DIAMONDS * math.sqrt(2)
    on_frame = min(u, v, 1 - u, 1 - v) < FRAME
    return (math.floor(s), math.floor(d)), on_came or on_frame


def base_colour(u, v):
    (a, b), lead = quarry(u, v)
    return LEAD if lead else GLASS[(a * 3 + b * 7) % len(GLASS)]


def transmission(u, v):
    return (0.0, 0.0, 0.0) if quarry(u, v)[1] else (1.0, 1.0, 1.0)


def main():
    turn = math.radians(15)
    gltf = {
        "asset": {"version": "2.0", "generator": "scenes/generate/make_leaded_window.py"},
        "extensionsUsed": ["KHR_materials_transmission"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "leaded window", "mesh": 0, "translation": [-0.1, 1.15, 0.6],
                   "rotation": [0.0, math.sin(turn / 2), 0.0, math.cos(turn / 2)], "scale": [1.15, 1.15, 1.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [
            {"name": "stained glass", "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.45},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0,
                                                           "transmissionTexture": {"index": 1}}}},
        ],
        "textures": [{"source": 0}, {"source": 1}],
        "images": [{"uri": data_uri("image/png", png(SIZE, SIZE, 3, base_colour))},
                   {"uri": data_uri("image/png", png(SIZE, SIZE, 3, transmission))}],
    }
    write_square_gltf(OUT, gltf)


if __name__ == "__main__":
    main()
