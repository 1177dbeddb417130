#!/usr/bin/env python3
"""Writes the project's scenes: OBJ meshes and MTL materials in scenes/meshes/ and scenes/materials/,
JSON scene files in scenes/. Standard library only. The outputs are committed; the build never runs
this script. Run it from anywhere: python3 scenes/generate/make_scenes.py

Every mesh object is checked before anything is written: closed (each edge used by exactly two
triangles, once in each direction: consistently wound), positive signed volume (counter-clockwise
seen from outside, so geometric normals point out), no degenerate triangle, and vertex normals on the
outer side. Every scene's camera is checked to see all its objects (the floor excepted).
"""

import json
import math
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # scenes/
MESHES = os.path.join(ROOT, "meshes")
MATERIALS = os.path.join(ROOT, "materials")


def fmt(x):
    """Shortest fixed-point text with 6 decimals at most; identical input gives identical text."""
    s = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    length = math.sqrt(dot(a, a))
    return (a[0] / length, a[1] / length, a[2] / length)


# ---- meshes ------------------------------------------------------------------------------------

class Mesh:
    """One closed object ("o" in the OBJ). Faces are triangles of vertex indices, each with optional
    per-corner normal indices and a material name."""

    def __init__(self, name):
        self.name = name
        self.vertices = []
        self.normals = []
        self.faces = []  # (v0, v1, v2), (n0, n1, n2) or None, material
        self._vertex_index = {}

    def vertex(self, p):
        key = tuple(fmt(c) for c in p)  # weld by the text written to the file
        if key not in self._vertex_index:
            self._vertex_index[key] = len(self.vertices)
            self.vertices.append(tuple(float(c) for c in key))
        return self._vertex_index[key]

    def normal(self, n):
        self.normals.append(normalize(n))
        return len(self.normals) - 1

    def tri(self, a, b, c, material, normals=None):
        self.faces.append(((a, b, c), normals, material))

    def quad(self, a, b, c, d, material, normals=None):
        """Counter-clockwise a, b, c, d."""
        self.tri(a, b, c, material, None if normals is None else (normals[0], normals[1], normals[2]))
        self.tri(a, c, d, material, None if normals is None else (normals[0], normals[2], normals[3]))

    def flip(self):
        self.faces = [((v[0], v[2], v[1]), None if n is None else (n[0], n[2], n[1]), m) for v, n, m in self.faces]

    def signed_volume(self):
        volume = 0.0
        for (a, b, c), _, _ in self.faces:
            volume += dot(self.vertices[a], cross(self.vertices[b], self.vertices[c])) / 6.0
        return volume

    def check(self):
        """Raises if the mesh is not closed, consistently wound and outward facing."""
        edges = {}
        for (a, b, c), _, _ in self.faces:
            for e in ((a, b), (b, c), (c, a)):
                edges[e] = edges.get(e, 0) + 1
        for (a, b), count in edges.items():
            if count != 1:
                raise ValueError(f"{self.name}: edge {a}-{b} used {count} times in the same direction")
            if edges.get((b, a), 0) != 1:
                raise ValueError(f"{self.name}: edge {a}-{b} has no opposite (open or inconsistently wound)")
        volume = self.signed_volume()
        if volume <= 0.0:
            raise ValueError(f"{self.name}: signed volume {volume} is not positive (wound inward)")
        for (a, b, c), ns, _ in self.faces:
            pa, pb, pc = self.vertices[a], self.vertices[b], self.vertices[c]
            g = cross(sub(pb, pa), sub(pc, pa))
            if dot(g, g) < 1e-20:
                raise ValueError(f"{self.name}: degenerate triangle {a} {b} {c}")
            if ns is not None:
                for n in ns:
                    if dot(self.normals[n], g) <= 0.0:
                        raise ValueError(f"{self.name}: vertex normal on the inner side of triangle {a} {b} {c}")
        return len(edges) // 2, volume


def box(name, lo, hi, material):
    """An axis-aligned box with flat faces (no vertex normals)."""
    m = Mesh(name)
    v = {}
    for i in (0, 1):
        for j in (0, 1):
            for k in (0, 1):
                v[i, j, k] = m.vertex((hi[0] if i else lo[0], hi[1] if j else lo[1], hi[2] if k else lo[2]))
    m.quad(v[0, 0, 0], v[0, 1, 0], v[1, 1, 0], v[1, 0, 0], material)  # -z
    m.quad(v[0, 0, 1], v[1, 0, 1], v[1, 1, 1], v[0, 1, 1], material)  # +z
    m.quad(v[0, 0, 0], v[1, 0, 0], v[1, 0, 1], v[0, 0, 1], material)  # -y
    m.quad(v[0, 1, 0], v[0, 1, 1], v[1, 1, 1], v[1, 1, 0], material)  # +y
    m.quad(v[0, 0, 0], v[0, 0, 1], v[0, 1, 1], v[0, 1, 0], material)  # -x
    m.quad(v[1, 0, 0], v[1, 1, 0], v[1, 1, 1], v[1, 0, 1], material)  # +x
    return m


def box_shell(name, lo, hi, thickness, material):
    """A closed box-shaped shell: the solid between an outer box and an inner box `thickness`
    inside it (the inner faces wound to face the cavity). A room with glass walls."""
    m = box(name, lo, hi, material)
    inner = box(name + "_cavity", tuple(c + thickness for c in lo), tuple(c - thickness for c in hi), material)
    inner.flip()
    offset = len(m.vertices)
    m.vertices += inner.vertices
    m.faces += [(tuple(i + offset for i in v), n, mat) for v, n, mat in inner.faces]
    return m


def uv_sphere(name, radius, segments, rings, material):
    """Latitude-longitude sphere with smooth normals: 2 * segments * (rings - 1) triangles."""
    m = Mesh(name)
    south = m.vertex((0.0, 0.0, -radius))
    north = m.vertex((0.0, 0.0, radius))
    ring = []
    for r in range(1, rings):
        theta = math.pi * r / rings  # from the south pole
        z = -radius * math.cos(theta)
        rr = radius * math.sin(theta)
        ring.append([m.vertex((rr * math.cos(2 * math.pi * s / segments), rr * math.sin(2 * math.pi * s / segments), z))
                     for s in range(segments)])
    normal_of = {}

    def n(vi):
        if vi not in normal_of:
            normal_of[vi] = m.normal(m.vertices[vi])
        return normal_of[vi]

    for s in range(segments):
        t = (s + 1) % segments
        a, b = ring[0][s], ring[0][t]
        m.tri(south, b, a, material, (n(south), n(b), n(a)))
        a, b = ring[-1][s], ring[-1][t]
        m.tri(north, a, b, material, (n(north), n(a), n(b)))
        for r in range(len(ring) - 1):
            a, b, c, d = ring[r][s], ring[r][t], ring[r + 1][t], ring[r + 1][s]
            m.quad(a, b, c, d, material, (n(a), n(b), n(c), n(d)))
    return m


def icosphere(name, radius, level, material):
    """Subdivided icosahedron with smooth normals: 20 * 4^level triangles."""
    g = (1.0 + math.sqrt(5.0)) / 2.0
    points = [normalize(p) for p in [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
                                     (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        midpoint = {}

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in midpoint:
                a, b = points[i], points[j]
                points.append(normalize(((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2)))
                midpoint[key] = len(points) - 1
            return midpoint[key]

        new_faces = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new_faces
    m = Mesh(name)
    index = [m.vertex((p[0] * radius, p[1] * radius, p[2] * radius)) for p in points]
    normal = [m.normal(p) for p in points]
    for a, b, c in faces:
        m.tri(index[a], index[b], index[c], material, (normal[a], normal[b], normal[c]))
    if m.signed_volume() < 0:
        m.flip()
    return m


def lathe(name, profile, segments, material):
    """A solid of revolution about the z axis. `profile` is a list of (r, z) points from the axis at the
    bottom, counter-clockwise around the solid's cross-section in the (r, z) half plane, back to the axis
    at the top; points with r == 0 are on the axis. Each profile segment is a band with its own normals
    (smooth around the axis, sharp at the profile's corners)."""
    m = Mesh(name)
    angles = [2.0 * math.pi * s / segments for s in range(segments)]

    def ring(r, z):
        if r == 0.0:
            return [m.vertex((0.0, 0.0, z))] * segments
        return [m.vertex((r * math.cos(a), r * math.sin(a), z)) for a in angles]

    rings = [ring(r, z) for r, z in profile]
    for k in range(len(profile) - 1):
        (r0, z0), (r1, z1) = profile[k], profile[k + 1]
        nr, nz = z1 - z0, -(r1 - r0)  # outward normal of the profile segment
        normals = [m.normal((nr * math.cos(a), nr * math.sin(a), nz)) for a in angles]
        lower, upper = rings[k], rings[k + 1]
        for s in range(segments):
            t = (s + 1) % segments
            ns, nt = normals[s], normals[t]
            if r0 == 0.0:
                m.tri(lower[s], upper[t], upper[s], material, (ns, nt, ns))
            elif r1 == 0.0:
                m.tri(lower[s], lower[t], upper[s], material, (ns, nt, ns))
            else:
                m.quad(lower[s], lower[t], upper[t], upper[s], material, (ns, nt, nt, ns))
    if m.signed_volume() < 0:
        m.flip()
    return m


def checker_floor(name, tiles, size, thickness, light, dark):
    """A slab whose top (z = 0) is tiles x tiles squares of `size` in alternating materials, centred on
    the origin; bottom and sides are `dark`. Closed: the sides and bottom share the top's subdivision."""
    m = Mesh(name)
    half = tiles * size / 2.0
    coords = [-half + i * size for i in range(tiles + 1)]
    top = [[m.vertex((x, y, 0.0)) for x in coords] for y in coords]  # top[j][i]
    bottom = [[m.vertex((x, y, -thickness)) for x in coords] for y in coords]
    for j in range(tiles):
        for i in range(tiles):
            material = light if (i + j) % 2 == 0 else dark
            m.quad(top[j][i], top[j][i + 1], top[j + 1][i + 1], top[j + 1][i], material)
            m.quad(bottom[j][i], bottom[j + 1][i], bottom[j + 1][i + 1], bottom[j][i + 1], dark)
    n = tiles
    for i in range(n):
        m.quad(bottom[0][i], bottom[0][i + 1], top[0][i + 1], top[0][i], dark)  # -y side
        m.quad(bottom[n][i + 1], bottom[n][i], top[n][i], top[n][i + 1], dark)  # +y side
        m.quad(bottom[i + 1][0], bottom[i][0], top[i][0], top[i + 1][0], dark)  # -x side
        m.quad(bottom[i][n], bottom[i + 1][n], top[i + 1][n], top[i][n], dark)  # +x side
    return m


def prism(name, corners, z0, z1, material):
    """A vertical prism over a counter-clockwise (seen from +z) polygon of (x, y) corners, flat faces."""
    m = Mesh(name)
    lower = [m.vertex((x, y, z0)) for x, y in corners]
    upper = [m.vertex((x, y, z1)) for x, y in corners]
    k = len(corners)
    for i in range(1, k - 1):
        m.tri(lower[0], lower[i + 1], lower[i], material)
        m.tri(upper[0], upper[i], upper[i + 1], material)
    for i in range(k):
        j = (i + 1) % k
        m.quad(lower[i], lower[j], upper[j], upper[i], material)
    return m


# ---- files -------------------------------------------------------------------------------------

written = []
mesh_stats = {}  # obj file name -> [(object, triangles, volume)]


def write_text(path, text):
    with open(path, "w", newline="\n") as f:
        f.write(text)
    written.append(os.path.relpath(path, os.path.dirname(ROOT)))


def write_obj(file_name, mtllib, meshes, comment):
    lines = [f"# {comment}", "# Generated by scenes/generate/make_scenes.py; z is up.", f"mtllib {mtllib}"]
    v_offset, n_offset = 1, 1
    stats = []
    for m in meshes:
        edges, volume = m.check()
        stats.append((m.name, len(m.faces), volume))
        lines.append(f"o {m.name}")
        lines += [f"v {fmt(x)} {fmt(y)} {fmt(z)}" for x, y, z in m.vertices]
        lines += [f"vn {fmt(x)} {fmt(y)} {fmt(z)}" for x, y, z in m.normals]
        material = None
        for (a, b, c), ns, mat in m.faces:
            if mat != material:
                lines.append(f"usemtl {mat}")
                material = mat
            if ns is None:
                lines.append(f"f {a + v_offset} {b + v_offset} {c + v_offset}")
            else:
                lines.append(f"f {a + v_offset}//{ns[0] + n_offset} {b + v_offset}//{ns[1] + n_offset} "
                             f"{c + v_offset}//{ns[2] + n_offset}")
        v_offset += len(m.vertices)
        n_offset += len(m.normals)
    write_text(os.path.join(MESHES, file_name), "\n".join(lines) + "\n")
    mesh_stats[file_name] = stats


def mtl_entry(name, shader, kd=(0.5, 0.5, 0.5), ka=(0.0, 0.0, 0.0), ks=(0.0, 0.0, 0.0), ns=1.0, ni=1.5,
              tf=(0.0, 0.0, 0.0), comment=None):
    illum = {2: 1, 3: 2, 4: 7, 6: 3}.get(shader, 2)  # for other MTL readers; vitrum reads `shader`
    lines = [f"# {comment}"] if comment else []
    lines += [f"newmtl {name}",
              "Ka " + " ".join(fmt(c) for c in ka),
              "Kd " + " ".join(fmt(c) for c in kd),
              "Ks " + " ".join(fmt(c) for c in ks),
              f"Ns {fmt(ns)}",
              f"Ni {fmt(ni)}",
              "Tf " + " ".join(fmt(c) for c in tf),
              f"illum {illum}",
              f"shader {shader}"]
    return "\n".join(lines) + "\n"


def write_mtl(directory, file_name, entries, comment):
    text = f"# {comment}\n# Generated by scenes/generate/make_scenes.py. Ka Kd Ks are sRGB; Tf is Beer-Lambert mu " \
           "per scene unit (glass only).\n\n" + "\n".join(entries)
    write_text(os.path.join(directory, file_name), text)


def compact_json(value):
    """Indented JSON with arrays of numbers on one line."""
    text = json.dumps(value, indent=2)
    return re.sub(r"\[\s*([-0-9.e,\s]+?)\s*\]", lambda m: "[" + ", ".join(m.group(1).split()).replace(",,", ",") + "]",
                  text)


# ---- camera check ------------------------------------------------------------------------------

def transform_point(p, t):
    if not t:
        return p
    s = t.get("scale", 1.0)
    x, y, z = p[0] * s, p[1] * s, p[2] * s
    rx, ry, rz = (math.radians(a) for a in t.get("rotate_deg", [0, 0, 0]))
    assert rx == 0 and ry == 0, "the scenes only rotate about z (no convention question)"
    x, y = x * math.cos(rz) - y * math.sin(rz), x * math.sin(rz) + y * math.cos(rz)
    d = t.get("translate", [0, 0, 0])
    return (x + d[0], y + d[1], z + d[2])


def check_camera(scene_name, scene, meshes_by_file):
    cam = scene["camera"]
    w, h = cam["width"], cam["height"]
    f = h / (2.0 * math.tan(math.radians(cam["fov_y"]) / 2.0))
    zc = normalize(sub(cam["from"], cam["at"]))
    xc = normalize(cross(cam["up"], zc))
    yc = cross(zc, xc)
    lo, hi = [math.inf, math.inf], [-math.inf, -math.inf]
    for obj in scene["objects"]:
        if "floor" in obj["obj"] or "room" in obj["obj"]:  # surroundings, not subjects
            continue
        for m in meshes_by_file[os.path.basename(obj["obj"])]:
            for p in m.vertices:
                d = sub(transform_point(p, obj.get("transform")), cam["from"])
                depth = -dot(d, zc)
                if depth <= 0:
                    raise ValueError(f"{scene_name}: {obj['obj']} is behind the camera")
                sx = w / 2 + f * dot(d, xc) / depth
                sy = h / 2 - f * dot(d, yc) / depth
                lo = [min(lo[0], sx), min(lo[1], sy)]
                hi = [max(hi[0], sx), max(hi[1], sy)]
    if lo[0] < 0 or lo[1] < 0 or hi[0] > w or hi[1] > h:
        raise ValueError(f"{scene_name}: objects span pixels x {lo[0]:.0f}..{hi[0]:.0f}, y {lo[1]:.0f}..{hi[1]:.0f}"
                         f" outside the {w}x{h} image")
    return lo, hi


# ---- the scenes --------------------------------------------------------------------------------

def main():
    os.makedirs(MESHES, exist_ok=True)
    os.makedirs(MATERIALS, exist_ok=True)
    meshes = {}

    def obj(file_name, mtllib, ms, comment):
        write_obj(file_name, mtllib, ms, comment)
        meshes[file_name] = ms

    # Materials. Meshes refer to a library next to them (meshes/*.mtl); scenes pick per-object
    # materials with "mtl" overrides from materials/, each defining the one material "surface".
    write_mtl(MESHES, "floor.mtl", [
        mtl_entry("floor_light", 2, ka=(0.05, 0.05, 0.05), kd=(0.85, 0.85, 0.82)),
        mtl_entry("floor_dark", 2, ka=(0.05, 0.05, 0.05), kd=(0.22, 0.24, 0.28)),
    ], "Checkerboard floor: two Lambert materials.")
    write_mtl(MESHES, "glass.mtl", [mtl_entry("surface", 4, ks=(1, 1, 1), ni=1.5, comment="Clear glass.")],
              "Default material of the shape meshes: clear glass.")
    write_mtl(MESHES, "water_glass.mtl", [
        mtl_entry("glass", 4, ks=(1, 1, 1), ni=1.5, tf=(0.02, 0.01, 0.02), comment="Tumbler glass, barely green."),
        mtl_entry("water", 4, ks=(1, 1, 1), ni=1.33, tf=(0.15, 0.04, 0.01), comment="Water, slightly blue."),
    ], "A tumbler of glass holding water.")
    overrides = {
        "clear_glass.mtl": ("Clear glass, Ni 1.5, no absorption.", mtl_entry("surface", 4, ks=(1, 1, 1), ni=1.5)),
        "tinted_glass.mtl": ("Blue-tinted glass: absorbs red most, green some, blue little.",
                             mtl_entry("surface", 4, ks=(1, 1, 1), ni=1.5, tf=(0.9, 0.35, 0.06))),
        "green_glass.mtl": ("The lecture's green glass.",
                            mtl_entry("surface", 4, ks=(1, 1, 1), ni=1.5, tf=(0.4, 0.001, 0.4))),
        "red_plastic.mtl": ("Red plastic: Phong plus Schlick-weighted reflection.",
                            mtl_entry("surface", 3, ka=(0.02, 0.0, 0.0), kd=(0.75, 0.06, 0.05), ks=(0.6, 0.6, 0.6),
                                      ns=40, ni=1.46)),
        "white_plastic.mtl": ("The lecture's white plastic.",
                              mtl_entry("surface", 3, ka=(0.01, 0.01, 0.01), kd=(0.95, 0.95, 0.95),
                                        ks=(0.8, 0.8, 0.8), ns=20, ni=1.46)),
        "black_plastic.mtl": ("The lecture's black plastic.",
                              mtl_entry("surface", 3, ka=(0.01, 0.01, 0.01), kd=(0.1, 0.1, 0.1), ks=(0.8, 0.8, 0.8),
                                        ns=20, ni=1.46)),
        "lambert_red.mtl": ("Matte red.", mtl_entry("surface", 2, ka=(0.03, 0.0, 0.0), kd=(0.8, 0.15, 0.1))),
        "lambert_white.mtl": ("Matte white.", mtl_entry("surface", 2, ka=(0.03, 0.03, 0.03), kd=(0.9, 0.9, 0.9))),
        "phong_blue.mtl": ("Shiny blue (opaque dielectric).",
                           mtl_entry("surface", 3, ka=(0.0, 0.0, 0.02), kd=(0.1, 0.25, 0.8), ks=(0.7, 0.7, 0.7),
                                     ns=60, ni=1.5)),
        "phong_gold.mtl": ("Shiny yellow (opaque dielectric).",
                           mtl_entry("surface", 3, ka=(0.02, 0.02, 0.0), kd=(0.85, 0.6, 0.1), ks=(0.5, 0.5, 0.5),
                                     ns=25, ni=1.5)),
        "air_bubble.mtl": ("Air enclosed in glass: a glass-model medium of IOR 1 and no absorption.",
                           mtl_entry("surface", 4, ks=(1, 1, 1), ni=1.0)),
        "lambert_blue.mtl": ("Matte blue.", mtl_entry("surface", 2, ka=(0.0, 0.0, 0.03), kd=(0.1, 0.2, 0.75))),
    }
    for name, (comment, entry) in overrides.items():
        write_mtl(MATERIALS, name, [entry], comment)

    # Meshes.
    obj("checker_floor.obj", "floor.mtl", [checker_floor("floor", 8, 1.0, 0.1, "floor_light", "floor_dark")],
        "Checkerboard floor: 8 x 8 unit tiles, top at z = 0, x and y in [-4, 4], 0.1 thick.")
    obj("sphere.obj", "glass.mtl", [uv_sphere("sphere", 1.0, 48, 22, "surface")],
        "Unit sphere (radius 1, centre at the origin), 48 x 22 latitude-longitude, smooth normals.")
    obj("icosphere5.obj", "glass.mtl", [icosphere("icosphere", 1.0, 5, "surface")],
        "Unit icosphere (radius 1, centre at the origin), level 5 subdivision, smooth normals.")
    obj("glass_room.obj", "glass.mtl", [box_shell("room", (-4.0, -4.0, -4.0), (4.0, 4.0, 4.0), 0.2, "surface")],
        "A closed room with glass walls: the shell between [-4, 4]^3 and [-3.8, 3.8]^3.")
    obj("cube.obj", "glass.mtl", [box("cube", (-0.5, -0.5, -0.5), (0.5, 0.5, 0.5), "surface")],
        "Unit cube, [-0.5, 0.5]^3.")
    obj("block.obj", "glass.mtl", [box("block", (-0.6, -0.35, 0.0), (0.6, 0.35, 1.6), "surface")],
        "Upright block 1.2 x 0.7 x 1.6 standing on z = 0.")
    obj("touching_cubes.obj", "glass.mtl",
        [box("cube_a", (-1.0, -0.5, -0.5), (0.0, 0.5, 0.5), "surface"),
         box("cube_b", (0.0, -0.5, -0.5), (1.0, 0.5, 0.5), "surface")],
        "Two unit cubes sharing the face x = 0 with identical coordinates: x in [-1, 0] and [0, 1].")
    obj("one_box.obj", "glass.mtl", [box("box", (-1.0, -0.5, -0.5), (1.0, 0.5, 0.5), "surface")],
        "One box of the outer shape of touching_cubes.obj: x in [-1, 1], y and z in [-0.5, 0.5].")
    # Right-angle prism: the right angle at (-1, -1), legs facing -y and -x, the hypotenuse facing +x +y.
    obj("prism.obj", "glass.mtl", [prism("prism", [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0)], 0.0, 1.5, "surface")],
        "Right-angle (45-45-90) glass prism 2 x 2 x 1.5 standing on z = 0: a ray entering the -y face along +y "
        "meets the hypotenuse at 45 degrees, beyond the critical angle of glass (41.8), and leaves through -x.")
    # Tumbler: outer radius 1, wall 0.08, bottom 0.2, height 2.4; water fills it to 1.6 and touches the
    # inner wall and bottom exactly (the same vertices: the inner wall is split at the water line).
    r_out, r_in, bottom, height, water = 1.0, 0.92, 0.2, 2.4, 1.6
    segments = 64
    tumbler = lathe("tumbler", [(0.0, 0.0), (r_out, 0.0), (r_out, height), (r_in, height), (r_in, water),
                                (r_in, bottom), (0.0, bottom)], segments, "glass")
    water_body = lathe("water", [(0.0, bottom), (r_in, bottom), (r_in, water), (0.0, water)], segments, "water")
    obj("water_glass.obj", "water_glass.mtl", [tumbler, water_body],
        f"A glass tumbler (Ni 1.5, radius {r_out}, wall {fmt(r_out - r_in)}, bottom {bottom}, height {height}) "
        f"with water (Ni 1.33) up to z = {water} touching its inner wall and bottom.")

    # Scenes.
    floor = {"obj": "meshes/checker_floor.obj"}
    render = {"spp": 1, "max_depth": 10, "fresnel": "schlick"}

    def camera(frm, at, fov=40, width=320, height=240):
        return {"from": frm, "at": at, "up": [0, 0, 1], "fov_y": fov, "width": width, "height": height}

    def shape(mesh, mtl, scale=None, translate=None, rotate_z=None):
        o = {"obj": "meshes/" + mesh, "mtl": "materials/" + mtl}
        t = {}
        if scale is not None:
            t["scale"] = scale
        if rotate_z is not None:
            t["rotate_deg"] = [0, 0, rotate_z]
        if translate is not None:
            t["translate"] = translate
        if t:
            o["transform"] = t
        return o

    lift = 0.01  # glass and boxes stand this far above the floor: no coplanar faces with it
    scenes = {
        "demo": {
            "about": "The default scene of `make demo`: a clear glass sphere and a blue-tinted glass block on a "
                        "checkerboard, a red plastic sphere behind them, two lights.",
            "camera": camera([1.2, -7.6, 3.4], [0.0, 0.4, 0.75], 32),
            "lights": [{"position": [5.0, -5.0, 8.0], "colour": [0.85, 0.83, 0.8]},
                       {"position": [-6.0, -3.0, 5.0], "colour": [0.3, 0.32, 0.38]}],
            "background": {"colour": [0.05, 0.06, 0.08]},
            "objects": [floor,
                        shape("sphere.obj", "clear_glass.mtl", translate=[-1.25, -0.4, 1.0]),
                        shape("block.obj", "tinted_glass.mtl", translate=[1.1, -0.3, lift], rotate_z=25),
                        shape("sphere.obj", "red_plastic.mtl", scale=0.6, translate=[0.1, 1.9, 0.6])],
            "render": render,
        },
        "lambert_spheres": {
            "about": "No glass: Lambert and Phong spheres on a Lambert checkerboard, one light.",
            "camera": camera([0.0, -7.0, 3.0], [0.0, 0.0, 0.7], 40),
            "lights": [{"position": [4.0, -4.0, 7.0], "colour": [1.0, 1.0, 1.0]}],
            "background": {"colour": [0.1, 0.1, 0.12]},
            "objects": [floor,
                        shape("sphere.obj", "lambert_red.mtl", scale=0.8, translate=[-1.8, 0.0, 0.8]),
                        shape("sphere.obj", "lambert_white.mtl", scale=0.8, translate=[0.0, 0.6, 0.8]),
                        shape("sphere.obj", "phong_blue.mtl", scale=0.8, translate=[1.8, 0.0, 0.8]),
                        shape("sphere.obj", "phong_gold.mtl", scale=0.4, translate=[-0.5, -1.6, 0.4])],
            "render": render,
        },
        "touching_cubes": {
            "about": "Two glass cubes sharing the face x = 0; must render like one_box.json (index-matched "
                        "interface: no reflection, no refraction at the shared face).",
            "camera": camera([2.2, -5.5, 2.3], [0.0, 0.0, 0.0], 40),
            "lights": [{"position": [4.0, -4.0, 6.0], "colour": [0.9, 0.9, 0.9]},
                       {"position": [-5.0, -2.0, 4.0], "colour": [0.3, 0.3, 0.35]}],
            "background": {"colour": [0.2, 0.22, 0.25]},
            "objects": [{"obj": "meshes/checker_floor.obj", "transform": {"translate": [0.0, 0.0, -0.5 - lift]}},
                        {"obj": "meshes/touching_cubes.obj", "mtl": "materials/clear_glass.mtl"}],
            "render": render,
        },
        "water_glass": {
            "about": "A glass tumbler (Ni 1.5) of water (Ni 1.33) whose surface touches the glass's inner wall "
                        "and bottom: glass-to-water interfaces 1.5 -> 1.33, never through air.",
            "camera": camera([0.6, -6.0, 3.4], [0.0, 0.0, 1.0], 36),
            "lights": [{"position": [4.0, -3.0, 7.0], "colour": [0.9, 0.9, 0.9]},
                       {"position": [-4.0, -4.0, 4.0], "colour": [0.3, 0.3, 0.35]}],
            "background": {"colour": [0.25, 0.3, 0.38]},
            "objects": [floor, {"obj": "meshes/water_glass.obj", "transform": {"translate": [0.0, 0.0, lift]}}],
            "render": render,
        },
        "bubble": {
            "about": "An air bubble (a sphere of IOR 1) inside a tinted glass block: nested media, glass -> air -> "
                        "glass, with Beer-Lambert absorption only in the glass around the bubble.",
            "camera": camera([2.2, -5.5, 2.6], [0.0, 0.0, 0.8], 36),
            "lights": [{"position": [3.0, -6.0, 6.0], "colour": [0.9, 0.9, 0.9]}],
            "background": {"colour": [0.3, 0.32, 0.36]},
            "objects": [floor,
                        shape("block.obj", "tinted_glass.mtl", scale=1.2, translate=[0.0, 0.0, lift]),
                        shape("sphere.obj", "air_bubble.mtl", scale=0.35, translate=[0.0, 0.0, 1.0])],
            "render": render,
        },
        "prism": {
            "about": "A right-angle glass prism seen through its front face: the hypotenuse behind reflects "
                        "totally (45 degrees inside, beyond the 41.8 degree critical angle), so the front face "
                        "shows the red sphere on the left instead of the blue cube behind.",
            "camera": camera([0.6, -7.5, 1.6], [-0.3, 0.0, 0.75], 40),
            "lights": [{"position": [3.0, -6.0, 6.0], "colour": [0.9, 0.9, 0.9]},
                       {"position": [-5.0, -2.0, 5.0], "colour": [0.35, 0.35, 0.35]}],
            "background": {"colour": [0.15, 0.16, 0.18]},
            "objects": [floor,
                        shape("prism.obj", "clear_glass.mtl", translate=[0.0, 0.0, lift]),
                        shape("sphere.obj", "red_plastic.mtl", scale=0.7, translate=[-3.0, 0.0, 0.7]),
                        shape("cube.obj", "lambert_blue.mtl", translate=[0.0, 2.6, 0.5 + lift])],
            "render": render,
        },
        "plastics_green_glass": {
            "about": "The lecture's exercise in spirit: white and black plastics (Ni 1.46, Ka 0.01, Kd 0.95 or "
                        "0.1, Ks 0.8, Ns 20) and one green glass (Ni 1.5, Tf 0.4 0.001 0.4).",
            "camera": camera([0.0, -7.5, 3.6], [0.0, 0.2, 0.6], 42),
            "lights": [{"position": [4.0, -5.0, 7.0], "colour": [0.8, 0.8, 0.8]},
                       {"position": [-5.0, -3.0, 6.0], "colour": [0.4, 0.4, 0.4]}],
            "background": {"colour": [0.3, 0.32, 0.35]},
            "objects": [floor,
                        shape("sphere.obj", "green_glass.mtl", translate=[0.0, 0.0, 1.0]),
                        shape("sphere.obj", "white_plastic.mtl", scale=0.6, translate=[-2.2, -0.6, 0.6]),
                        shape("sphere.obj", "black_plastic.mtl", scale=0.6, translate=[2.2, -0.6, 0.6]),
                        shape("cube.obj", "white_plastic.mtl", scale=0.9, rotate_z=30,
                              translate=[1.6, 1.8, 0.45 + lift]),
                        shape("cube.obj", "black_plastic.mtl", scale=0.9, rotate_z=-20,
                              translate=[-1.6, 1.8, 0.45 + lift]),
                        shape("sphere.obj", "white_plastic.mtl", scale=0.35, translate=[0.9, -2.0, 0.35])],
            "render": render,
        },
        "loop_limit": {
            "about": "A clear glass icosphere of 20,480 triangles inside a closed room with glass walls, seen "
                        "from inside the room over a checker floor, 32x24 at 6 spp, max_depth 10: nearly every ray "
                        "meets glass, so a pixel's trees have thousands of rays, each walking the BVH: far more "
                        "than 65,535 loop iterations.",
            "camera": camera([0.0, -2.7, 0.0], [0.0, 0.0, 0.0], 45, 32, 24),
            "lights": [{"position": [1.5, -2.0, 2.5], "colour": [1.0, 1.0, 1.0]}],
            "background": {"colour": [0.6, 0.65, 0.7]},
            "objects": [shape("icosphere5.obj", "clear_glass.mtl"), shape("glass_room.obj", "clear_glass.mtl"),
                        {"obj": "meshes/checker_floor.obj", "transform": {"scale": 0.9, "translate": [0, 0, -1.2]}}],
            "render": {"spp": 6, "max_depth": 10, "fresnel": "schlick"},
        },
    }
    scenes["one_box"] = json.loads(json.dumps(scenes["touching_cubes"]))
    scenes["one_box"]["about"] = "One glass box of the same outer shape as touching_cubes.json, same camera, " \
                                    "lights and floor: the reference it must match."
    scenes["one_box"]["objects"][1]["obj"] = "meshes/one_box.obj"

    report = []
    about = []
    for name, scene in scenes.items():
        lo, hi = check_camera(name, scene, meshes)
        triangles = 0
        for o in scene["objects"]:
            triangles += sum(len(m.faces) for m in meshes[os.path.basename(o["obj"])])
        about.append((name, triangles, scene.pop("about")))
        text = compact_json(scene)
        write_text(os.path.join(ROOT, name + ".json"), text + "\n")
        report.append(f"  {name + '.json':28s} {triangles:6d} triangles; objects at pixels "
                      f"x {lo[0]:.0f}..{hi[0]:.0f}, y {lo[1]:.0f}..{hi[1]:.0f} of "
                      f"{scene['camera']['width']}x{scene['camera']['height']}")

    readme = ["# Scenes", "",
              "Generated by `generate/make_scenes.py` (python3, standard library only); the generated files are",
              "committed and the build never runs the script. Format: `docs/scene-format.md`. World is z-up.",
              "Meshes (`meshes/`) are closed, consistently wound (counter-clockwise seen from outside) and",
              "checked so by the script. Shape meshes use one material `surface`; scenes pick it per object",
              "with an `mtl` override from `materials/`.", "",
              "| scene | triangles | what it shows |", "|---|---|---|"]
    readme += [f"| `{name}.json` | {tris:,} | {text} |" for name, tris, text in about]
    # The README's section on the scenes written by hand is kept as it is.
    readme_path = os.path.join(ROOT, "README.md")
    hand_written = ""
    if os.path.exists(readme_path):
        with open(readme_path, encoding="utf-8") as f:
            old_text = f.read()
        marker = "\nWritten by hand"
        if marker in old_text:
            hand_written = old_text[old_text.index(marker):]
    write_text(readme_path, "\n".join(readme) + "\n" + hand_written)

    print("meshes (closed, consistently wound, outward: checked):")
    for file_name, stats in mesh_stats.items():
        for obj_name, tris, volume in stats:
            print(f"  {file_name:22s} o {obj_name:14s} {tris:6d} triangles, volume {volume:.4f}")
    print("scenes (camera sees every object but the floor: checked):")
    print("\n".join(report))
    print(f"wrote {len(written)} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
