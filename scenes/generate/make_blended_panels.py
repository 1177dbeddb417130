#!/usr/bin/env python3
"""Writes scenes/meshes/blended_panels.gltf for scenes/blended.json: two squares of glTF's
`alphaMode` BLEND, partly there (docs/render-model-decisions.md, "Partial coverage"): a lace
curtain (Lambert, KHR_materials_specular's specularFactor 0) whose alpha is painted: fabric a
little over half there, denser rings around round holes where none is, a dense hem; and a sheet of
smoked acrylic (an opaque dielectric) 45% there everywhere, from its baseColorFactor alone. The
image and the buffer are embedded as data URIs. Standard library only; the output is committed and
the build never runs this. glTF is +Y up: vitrum places (x, y, z) at (x, -z, y)."""

import base64
import json
import math
import os
import struct
import zlib

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "meshes", "blended_panels.gltf")


def rgba_png(width, height, alpha):
    """White RGBA, alpha(u, v) in [0, 1] at pixel centres, v down from the top row."""
    rows = b""
    for y in range(height):
        row = bytearray(b"\x00")
        for x in range(width):
            a = max(0, min(255, round(255 * alpha((x + 0.5) / width, (y + 0.5) / height))))
            row += bytes((255, 255, 255, a))
        rows += bytes(row)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


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
    # A square from (-1, -1) to (1, 1) in glTF's xy plane, facing +z; uv (0, 0) at the top left.
    positions = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
    normals = [0, 0, 1] * 4
    uvs = [0, 1, 1, 1, 1, 0, 0, 0]
    indices = [0, 1, 2, 0, 2, 3]
    data = (struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<8f", *uvs) +
            struct.pack("<6H", *indices))
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
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(rgba_png(192, 192, lace)).decode()}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
            {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }
    with open(OUT, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
