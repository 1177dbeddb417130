"""What the glTF generators of scenes/generate share: a square mesh embedded as a data URI, and
8-bit PNG images painted by a function of (u, v). Standard library only."""

import base64
import json
import struct
import zlib


def png(width, height, channels, colour):
    """An 8-bit RGB (3 channels) or RGBA (4) PNG, colour(u, v) a tuple of values in [0, 1] at
    pixel centres, v down from the top row."""
    rows = b""
    for y in range(height):
        row = bytearray(b"\x00")
        for x in range(width):
            row += bytes(max(0, min(255, round(255 * c))) for c in colour((x + 0.5) / width, (y + 0.5) / height))
        rows += bytes(row)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    colour_type = {3: 2, 4: 6}[channels]
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def data_uri(kind, data):
    return "data:" + kind + ";base64," + base64.b64encode(data).decode()


def write_square_gltf(path, gltf):
    """Writes `gltf` (asset, scenes, nodes, meshes, materials, textures, images) with its buffer,
    views and accessors: a square from (-1, -1) to (1, 1) in glTF's xy plane, facing +z, uv (0, 0)
    at its top left, whose primitive attributes are POSITION 0, NORMAL 1, TEXCOORD_0 2, indices 3."""
    positions = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
    normals = [0, 0, 1] * 4
    uvs = [0, 1, 1, 1, 1, 0, 0, 0]
    indices = [0, 1, 2, 0, 2, 3]
    data = (struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<8f", *uvs) +
            struct.pack("<6H", *indices))
    gltf["buffers"] = [{"byteLength": len(data), "uri": data_uri("application/octet-stream", data)}]
    gltf["bufferViews"] = [
        {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
        {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
        {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
        {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963},
    ]
    gltf["accessors"] = [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ]
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
