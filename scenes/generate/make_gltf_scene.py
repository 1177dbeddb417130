#!/usr/bin/env python3
"""Writes scenes/meshes/glass_set.gltf (with glass_set.bin beside it): glasses of different IOR and
attenuation on a checker floor, as glTF 2.0 with KHR_materials_transmission, KHR_materials_volume
and KHR_materials_ior, a camera and a KHR_lights_punctual point light, so that it renders as a
scene of its own (`vitrum render scenes/meshes/glass_set.gltf`) and inside scenes/glass_set.json.
The three tumblers are one mesh's data: their meshes share its accessors, each with its own glass.
Also scenes/meshes/sapphire.gltf, one file with its buffer in a data URI: a cut gem of glass whose
surface the base colour tints (KHR_materials_volume, "Base Color and Absorption"), which
scenes/glass_set.json places in front of the set.
Standard library only; the outputs are committed. Run it from anywhere:
python3 scenes/generate/make_gltf_scene.py

Meshes come from make_scenes.py and are checked as it checks them (closed, outward). Coordinates are
written in glTF's +Y up: vitrum's (x, y, z) is glTF's (x, z, -y) (docs/scene-format.md, "glTF 2.0").
"""

import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_scenes import MESHES, checker_floor, cross, icosphere, lathe, normalize, sub  # noqa: E402


def to_gltf(p):
    return (p[0], p[2], -p[1])


class Buffer:
    """The .bin: accessors of float VEC3 and uint32 indices, each in a buffer view of its own."""

    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def _view(self, payload, target):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload), "target": target})
        self.data += payload
        return len(self.views) - 1

    def vec3(self, values):
        view = self._view(b"".join(struct.pack("<3f", *v) for v in values), 34962)
        lo = [min(v[k] for v in values) for k in range(3)]
        hi = [max(v[k] for v in values) for k in range(3)]
        # The bounds glTF asks of POSITION, as the float32 values written.
        lo = [struct.unpack("<f", struct.pack("<f", x))[0] for x in lo]
        hi = [struct.unpack("<f", struct.pack("<f", x))[0] for x in hi]
        self.accessors.append({"bufferView": view, "componentType": 5126, "count": len(values), "type": "VEC3",
                               "min": lo, "max": hi})
        return len(self.accessors) - 1

    def indices(self, values):
        view = self._view(struct.pack(f"<{len(values)}I", *values), 34963)
        self.accessors.append({"bufferView": view, "componentType": 5125, "count": len(values), "type": "SCALAR"})
        return len(self.accessors) - 1


def primitives(buffer, mesh, materials):
    """One primitive per material of `mesh`, each with its own vertices: a corner with a normal of its
    own is a vertex of its own (glTF has one normal a vertex); flat faces get no NORMAL (the geometric
    normal). Returns {material name: primitive}."""
    mesh.check()
    out = {}
    for material in sorted({m for _, _, m in mesh.faces}):
        faces = [(v, n) for v, n, m in mesh.faces if m == material]
        smooth = all(n is not None for _, n in faces)
        if not smooth and any(n is not None for _, n in faces):
            raise ValueError(f"{mesh.name}: material {material} mixes flat and smooth faces")
        corner_index, positions, normals, indices = {}, [], [], []
        for v, n in faces:
            for k in range(3):
                key = (v[k], n[k] if smooth else None)
                if key not in corner_index:
                    corner_index[key] = len(positions)
                    positions.append(to_gltf(mesh.vertices[v[k]]))
                    if smooth:
                        normals.append(to_gltf(mesh.normals[n[k]]))
                indices.append(corner_index[key])
        attributes = {"POSITION": buffer.vec3(positions)}
        if smooth:
            attributes["NORMAL"] = buffer.vec3(normals)
        out[material] = {"attributes": attributes, "indices": buffer.indices(indices), "mode": 4,
                         "material": materials[material]}
    return out


def glass(name, ior, attenuation=None, distance=None, tint=(1, 1, 1)):
    """A glass volume: absorption inside (attenuationColor after attenuationDistance), a tint at its
    surface (the base colour)."""
    volume = {"thicknessFactor": 0.1}
    if attenuation is not None:
        volume.update({"attenuationColor": list(attenuation), "attenuationDistance": distance})
    return {"name": name,
            "pbrMetallicRoughness": {"baseColorFactor": list(tint) + [1], "metallicFactor": 0.0, "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                           "KHR_materials_volume": volume, "KHR_materials_ior": {"ior": ior}}}


def diffuse(name, colour):
    # specularFactor 0: vitrum's Lambert (docs/scene-format.md's mapping table).
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1.0], "metallicFactor": 0.0,
                                                   "roughnessFactor": 1.0},
            "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}


def look_at_matrix(frm, at, up):
    """A glTF camera node's matrix (column-major): it looks down its local -z with +y up."""
    f = normalize(sub(at, frm))
    r = normalize(cross(f, up))
    u = cross(r, f)
    return [r[0], r[1], r[2], 0.0, u[0], u[1], u[2], 0.0, -f[0], -f[1], -f[2], 0.0, frm[0], frm[1], frm[2], 1.0]


def main():
    material_list = [
        diffuse("floor_light", (0.8, 0.8, 0.77)),
        diffuse("floor_dark", (0.12, 0.14, 0.18)),
        glass("clear_glass", 1.5),
        glass("green_glass", 1.52, (0.3, 0.75, 0.4), 0.12),
        glass("amber_flint", 1.72, (0.9, 0.55, 0.2), 0.12),
        glass("water", 1.33, (0.55, 0.8, 0.95), 0.5),
        glass("diamond", 2.42),
    ]
    materials = {m["name"]: i for i, m in enumerate(material_list)}
    buffer = Buffer()

    floor = primitives(buffer, checker_floor("floor", 8, 0.75, 0.1, "floor_light", "floor_dark"), materials)
    r_out, r_in, bottom, height = 0.5, 0.45, 0.12, 1.1
    tumbler = primitives(buffer, lathe("tumbler", [(0.0, 0.0), (r_out, 0.0), (r_out, height), (r_in, height),
                                                   (r_in, bottom), (0.0, bottom)], 48, "clear_glass"), materials)["clear_glass"]
    ball = primitives(buffer, icosphere("ball", 0.45, 3, "water"), materials)["water"]
    gem_mesh = icosphere("gem", 0.3, 1, "diamond")
    gem_mesh.faces = [(v, None, m) for v, _, m in gem_mesh.faces]  # cut facets: flat
    gem = primitives(buffer, gem_mesh, materials)["diamond"]

    def with_material(primitive, name):
        return dict(primitive, material=materials[name])

    meshes = [{"name": "floor", "primitives": [floor["floor_light"], floor["floor_dark"]]}]
    nodes = [{"name": "floor", "mesh": 0}]
    # vitrum's (x, y) on the floor -> glTF translation (x, z, -y).
    placed = [("clear tumbler", with_material(tumbler, "clear_glass"), (-1.3, 0.2, 0.0)),
              ("green tumbler", with_material(tumbler, "green_glass"), (0.0, 0.6, 0.0)),
              ("amber tumbler", with_material(tumbler, "amber_flint"), (1.3, 0.2, 0.0)),
              ("water ball", ball, (-0.65, -0.9, 0.45)),
              ("gem", gem, (0.75, -0.9, 0.2552))]
    for name, primitive, at in placed:
        meshes.append({"name": name, "primitives": [primitive]})
        nodes.append({"name": name, "mesh": len(meshes) - 1, "translation": list(to_gltf(at))})
    frm, at = (0.0, -5.2, 2.6), (0.0, 0.0, 0.45)
    nodes.append({"name": "camera", "camera": 0,
                  "matrix": look_at_matrix(to_gltf(frm), to_gltf(at), to_gltf((0.0, 0.0, 1.0)))})
    nodes.append({"name": "light", "translation": list(to_gltf((-2.5, -3.0, 5.0))),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})

    gltf = {
        "asset": {"version": "2.0", "generator": "vitrum scenes/generate/make_gltf_scene.py"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior",
                           "KHR_materials_specular", "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "key", "type": "point", "color": [1.0, 0.97, 0.9], "intensity": 45.0}]}},
        "scene": 0,
        "scenes": [{"name": "glass set", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"name": "front", "type": "perspective",
                     "perspective": {"yfov": math.radians(38.0), "aspectRatio": 4.0 / 3.0, "znear": 0.1}}],
        "meshes": meshes,
        "materials": material_list,
        "buffers": [{"uri": "glass_set.bin", "byteLength": len(buffer.data)}],
        "bufferViews": buffer.views,
        "accessors": buffer.accessors,
    }
    with open(os.path.join(MESHES, "glass_set.bin"), "wb") as f:
        f.write(bytes(buffer.data))
    with open(os.path.join(MESHES, "glass_set.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def sapphire():
    """A gem of corundum (n 1.77) whose surface tints blue, resting on the floor in front of the set."""
    materials = [glass("sapphire", 1.77, tint=(0.45, 0.6, 1.0))]
    buffer = Buffer()
    mesh = icosphere("sapphire", 0.22, 1, "sapphire")
    mesh.faces = [(v, None, m) for v, _, m in mesh.faces]  # cut facets: flat
    primitive = primitives(buffer, mesh, {"sapphire": 0})["sapphire"]
    lowest = min(v[2] for v in mesh.vertices)
    gltf = {
        "asset": {"version": "2.0", "generator": "vitrum scenes/generate/make_gltf_scene.py"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior"],
        "scene": 0,
        "scenes": [{"name": "sapphire", "nodes": [0]}],
        "nodes": [{"name": "sapphire", "mesh": 0, "translation": list(to_gltf((0.05, -1.55, -lowest + 1e-3)))}],
        "meshes": [{"name": "sapphire", "primitives": [primitive]}],
        "materials": materials,
        "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buffer.data)).decode(),
                     "byteLength": len(buffer.data)}],
        "bufferViews": buffer.views,
        "accessors": buffer.accessors,
    }
    with open(os.path.join(MESHES, "sapphire.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
    sapphire()
