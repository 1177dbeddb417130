#!/usr/bin/env python3
"""Writes scenes/meshes/blended_panels.gltf for scenes/blended.json: two squares of glTF's
`alphaMode` BLEND, partly there (docs/render-model-decisions.md, "Partial coverage"): a lace
curtain (Lambert, KHR_materials_specular's specularFactor 0) whose alpha is painted: fabric a
little over half there, denser rings around round holes where none is, a dense hem; and a sheet of
smoked acrylic (an opaque dielectric) 45% there everywhere, from its baseColorFactor alone. The
image and the buffer are embedded as data URIs. Standard library only; the output is committed and
the build never runs this. glTF is +Y up: vitrum places (x, y, z) at (x, -z, y)."""

import math
import os

from gltf_square import data_uri, png, write_square_gltf

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "meshes", "blended_panels.gltf")


def lace(u, v):
    """Round holes on a staggered grid, each in a denser ring; a dense hem at the bottom."""
    if v > 0.9:
        return 0.9
    cells = 6
    row = math.floor(v * cells)
    shift = 0.5 if row % 2 else 0.0
    cu = (math.floor(u * cells - shift) + 0.5 + shift) / cells
    cv = (row + 0.5) / cells
    r = math.hypot(u - cu, v - cv) * cells
    if r < 0.22:
        return 0.0
    if r < 0.34:
        return 0.9
    return 0.55


def main():
    turn = math.radians(-20)
    gltf = {
        "asset": {"version": "2.0", "generator": "scenes/generate/make_blended_panels.py"},
        "extensionsUsed": ["KHR_materials_specular"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "lace curtain", "mesh": 0, "translation": [-0.8, 1.05, 1.5], "scale": [1.1, 1.0, 1.0]},
            {"name": "smoked acrylic", "mesh": 1, "translation": [1.35, 0.85, 1.0],
             "rotation": [0.0, math.sin(turn / 2), 0.0, math.cos(turn / 2)], "scale": [0.65, 0.8, 1.0]},
        ],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 1}]},
        ],
        "materials": [
            {"name": "lace", "alphaMode": "BLEND", "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.92, 0.85, 1.0], "baseColorTexture": {"index": 0},
                                      "metallicFactor": 0.0, "roughnessFactor": 1.0},
             "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}},
            {"name": "smoked acrylic", "alphaMode": "BLEND", "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorFactor": [0.04, 0.04, 0.05, 0.45], "metallicFactor": 0.0,
                                      "roughnessFactor": 0.05}},
        ],
        "textures": [{"source": 0}],
        "images": [{"uri": data_uri("image/png", png(192, 192, 4, lambda u, v: (1.0, 1.0, 1.0, lace(u, v))))}],
    }
    write_square_gltf(OUT, gltf)


if __name__ == "__main__":
    main()
