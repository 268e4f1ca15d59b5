#!/usr/bin/env python3
"""Writes the bundled default scene: assets/room/room.gltf + room.bin + small PNG textures.

The room is generated, not modelled, so its exact geometry is known to the ground-truth
tracer and the file can be rebuilt identically. Standard library only.

Layout (metres, right-handed, Y up, as glTF):
  * room 8 x 8 x 4 centred at the origin, floor at y = 0, no ceiling (open to the sky);
    walls face INTO the room;
  * four 0.3 m square, 3 m tall columns of distinct saturated colours, 2.5 m from the centre
    on the diagonals;
  * three textured panels 2 cm in front of the north, east and west walls;
  * a table (node with children: top + 4 legs) against the north wall;
  * two mirror reflectors around the probe at (0, 1.2, 0): a sphere (r 0.5) and a torus;
  * the probe node and a perspective camera 3.5 m away looking at the reflectors.
Nothing but the reflectors comes within 2 m of the probe centre, and they keep 0.15 m clear.
"""
import json
import math
import os
import struct
import sys
import zlib

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
OUT_DIR = os.path.join(ROOT, "assets", "room")

PROBE = (0.0, 1.2, 0.0)


# ---------------------------------------------------------------- textures
def write_png(path, width, height, pixel):
    """pixel(x, y) -> (r, g, b) in 0..255, sRGB-encoded as PNG colour is."""
    raw = bytearray()
    for y in range(height):
        raw.append(0)  # filter type None
        for x in range(width):
            raw.extend(pixel(x, y))

    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def checker(x, y):
    return (200, 200, 190) if ((x // 8) + (y // 8)) % 2 == 0 else (60, 60, 70)


def stripes(x, y):
    band = ((x + y) // 8) % 4
    return [(220, 60, 40), (240, 200, 40), (40, 120, 220), (240, 240, 240)][band]


def grid(x, y):
    line = x % 16 in (0, 1) or y % 16 in (0, 1)
    return (30, 30, 30) if line else (90, 190, 120)


TEXTURES = [("floor_tiles.png", checker), ("panel_stripes.png", stripes), ("panel_grid.png", grid)]


# ---------------------------------------------------------------- geometry
def unit_quad():
    """1 x 1 quad in the XY plane, centred, facing +Z (counter-clockwise seen from +Z)."""
    pos = [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.5, 0.5, 0.0), (-0.5, 0.5, 0.0)]
    nrm = [(0.0, 0.0, 1.0)] * 4
    uv = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]
    return pos, nrm, uv, [0, 1, 2, 0, 2, 3]


def unit_box():
    """1 x 1 x 1 box centred at the origin, outward faces, flat normals (24 vertices)."""
    pos, nrm, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            # Two tangents chosen so that (u, v, n) is right-handed: CCW seen from outside.
            u = [0.0, 0.0, 0.0]
            v = [0.0, 0.0, 0.0]
            u[(axis + 1) % 3] = 1.0
            v[(axis + 2) % 3] = 1.0
            if sign < 0:
                u, v = v, u
            base = len(pos)
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.5 * n[i] + 0.5 * su * u[i] + 0.5 * sv * v[i] for i in range(3)]
                pos.append(tuple(p))
                nrm.append(tuple(n))
                uv.append(((su + 1) / 2, 1 - (sv + 1) / 2))
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def uv_sphere(radius, segments, rings):
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            pos.append(tuple(radius * c for c in n))
            nrm.append(n)
            uv.append((s / segments, r / rings))
    row = segments + 1
    for r in range(rings):
        for s in range(segments):
            a, b = r * row + s, r * row + s + 1
            c, d = (r + 1) * row + s, (r + 1) * row + s + 1
            if r != 0:
                idx += [a, c, b]
            if r != rings - 1:
                idx += [b, c, d]
    return pos, nrm, uv, idx


def torus(major, minor, segments, sides):
    pos, nrm, uv, idx = [], [], [], []
    for i in range(segments + 1):
        u = 2 * math.pi * i / segments
        cu, su = math.cos(u), math.sin(u)
        for j in range(sides + 1):
            v = 2 * math.pi * j / sides
            cv, sv = math.cos(v), math.sin(v)
            n = (cv * cu, sv, -cv * su)
            pos.append(((major + minor * cv) * cu, minor * sv, -(major + minor * cv) * su))
            nrm.append(n)
            uv.append((i / segments, j / sides))
    row = sides + 1
    for i in range(segments):
        for j in range(sides):
            a, b = i * row + j, i * row + j + 1
            c, d = (i + 1) * row + j, (i + 1) * row + j + 1
            idx += [a, c, b, b, c, d]
    return pos, nrm, uv, idx


# ---------------------------------------------------------------- glTF assembly
class Builder:
    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors, self.meshes, self.nodes, self.materials = [], [], [], [], []

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data),
                           "target": target})
        self.bin.extend(data)
        return len(self.views) - 1

    def _floats(self, rows, kind):
        data = b"".join(struct.pack("<%df" % len(r), *r) for r in rows)
        acc = {"bufferView": self._view(data, 34962), "componentType": 5126, "count": len(rows),
               "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(r[i] for r in rows) for i in range(3)]
            acc["max"] = [max(r[i] for r in rows) for i in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def geometry(self, geom):
        pos, nrm, uv, idx = geom
        small = max(idx) < 65536
        data = struct.pack("<%d%s" % (len(idx), "H" if small else "I"), *idx)
        self.accessors.append({"bufferView": self._view(data, 34963),
                               "componentType": 5123 if small else 5125, "count": len(idx),
                               "type": "SCALAR"})
        indices = len(self.accessors) - 1
        return {"POSITION": self._floats(pos, "VEC3"), "NORMAL": self._floats(nrm, "VEC3"),
                "TEXCOORD_0": self._floats(uv, "VEC2")}, indices

    def material(self, name, color, texture=None):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1.0],
                                                    "metallicFactor": 0.0,
                                                    "roughnessFactor": 1.0}}
        if texture is not None:
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
        self.materials.append(m)
        return len(self.materials) - 1

    def mesh(self, name, geom, material):
        attributes, indices = geom
        self.meshes.append({"name": name, "primitives": [
            {"attributes": attributes, "indices": indices, "material": material, "mode": 4}]})
        return len(self.meshes) - 1

    def node(self, name, **kw):
        n = {"name": name}
        for key in ("translation", "rotation", "scale"):
            if key in kw:
                n[key] = [round(float(c), 6) for c in kw[key]]
        for key in ("mesh", "camera", "children", "extras"):
            if key in kw:
                n[key] = kw[key]
        self.nodes.append(n)
        return len(self.nodes) - 1


def quat_axis(axis, degrees):
    h = math.radians(degrees) / 2
    s = math.sin(h)
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(h))


def build_room(b):
    """Adds the room without its reflectors (floor, walls, columns, panels, table) to `b`;
    returns the root nodes. Textures are TEXTURES' indices. Shared with make_bowl_room.py."""
    quad = b.geometry(unit_quad())
    box = b.geometry(unit_box())

    tex_floor, tex_stripes, tex_grid = 0, 1, 2
    roots = []

    # Floor and walls: the unit quad faces +Z; each is rotated so it faces into the room.
    floor = b.material("floor", (0.9, 0.9, 0.9), tex_floor)
    roots.append(b.node("floor", mesh=b.mesh("floor", quad, floor),
                        rotation=quat_axis((1, 0, 0), -90), scale=(8, 8, 1)))
    walls = [("wall_north", (0, 2, -4), 0, (0.80, 0.74, 0.62)),
             ("wall_south", (0, 2, 4), 180, (0.58, 0.68, 0.80)),
             ("wall_east", (4, 2, 0), -90, (0.70, 0.80, 0.58)),
             ("wall_west", (-4, 2, 0), 90, (0.80, 0.62, 0.70))]
    for name, t, yaw, color in walls:
        mat = b.material(name, color)
        roots.append(b.node(name, mesh=b.mesh(name, quad, mat), translation=t,
                            rotation=quat_axis((0, 1, 0), yaw), scale=(8, 4, 1)))

    # Columns on the diagonals, 2.5 m from the centre.
    d = 2.5 / math.sqrt(2)
    columns = [("column_red", (d, -d), (0.85, 0.05, 0.04)),
               ("column_green", (-d, -d), (0.05, 0.70, 0.10)),
               ("column_blue", (-d, d), (0.05, 0.15, 0.85)),
               ("column_yellow", (d, d), (0.90, 0.75, 0.05))]
    for name, (x, z), color in columns:
        mat = b.material(name, color)
        roots.append(b.node(name, mesh=b.mesh(name, box, mat), translation=(x, 1.5, z),
                            scale=(0.3, 3.0, 0.3)))

    # Textured panels 2 cm in front of the walls.
    panels = [("panel_stripes", (-1.2, 2.0, -3.98), 0, (1.6, 1.2, 1), tex_stripes),
              ("panel_grid", (3.98, 1.8, 0.0), -90, (2.0, 1.2, 1), tex_grid),
              ("panel_tiles", (-3.98, 1.8, 0.8), 90, (1.4, 1.4, 1), tex_floor)]
    for name, t, yaw, s, tex in panels:
        mat = b.material(name, (1, 1, 1), tex)
        roots.append(b.node(name, mesh=b.mesh(name, quad, mat), translation=t,
                            rotation=quat_axis((0, 1, 0), yaw), scale=s))

    # Table: one parent node, children placed in its frame (top 0.75 m high).
    wood = b.material("table_wood", (0.45, 0.28, 0.14))
    top_mesh = b.mesh("table_top", box, wood)
    children = [b.node("table_top", mesh=top_mesh, translation=(0, 0.75, 0),
                       scale=(1.6, 0.06, 0.9))]
    leg_mesh = b.mesh("table_leg", box, wood)
    for i, (x, z) in enumerate(((-0.72, -0.38), (0.72, -0.38), (0.72, 0.38), (-0.72, 0.38))):
        children.append(b.node("table_leg_%d" % i, mesh=leg_mesh, translation=(x, 0.36, z),
                               scale=(0.06, 0.72, 0.06)))
    roots.append(b.node("table", translation=(0, 0, -2.6), children=children))
    return roots


def finish(b, roots, scene_name, generator, bin_name):
    """Appends the probe and the camera to `roots`; returns the glTF document of `b` (with
    TEXTURES as its images, `bin_name` as its one buffer)."""
    roots.append(b.node("probe", translation=PROBE, extras={"specula_probe": {"cell_size": 2.0}}))

    # Camera 3.5 m from the probe, looking at it (glTF cameras look down local -Z).
    eye = (0.0, 1.6, 3.48)
    to = [PROBE[i] - eye[i] for i in range(3)]
    pitch = math.degrees(math.atan2(to[1], math.hypot(to[0], to[2])))
    roots.append(b.node("camera", camera=0, translation=eye, rotation=quat_axis((1, 0, 0), pitch)))

    return {
        "asset": {"version": "2.0", "generator": generator},
        "scene": 0,
        "scenes": [{"name": scene_name, "nodes": roots}],
        "nodes": b.nodes,
        "meshes": b.meshes,
        "materials": b.materials,
        "textures": [{"sampler": 0, "source": i} for i in range(len(TEXTURES))],
        "images": [{"uri": name, "name": name} for name, _ in TEXTURES],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "cameras": [{"type": "perspective", "name": "camera",
                     "perspective": {"yfov": 0.9, "aspectRatio": 16 / 9, "znear": 0.05,
                                     "zfar": 100.0}}],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"uri": bin_name, "byteLength": len(b.bin)}],
    }


def build():
    b = Builder()
    roots = build_room(b)
    # The room added only the quad and the box to the buffer, so these follow them there.
    sphere = b.geometry(uv_sphere(0.32, 32, 32))
    ring = b.geometry(torus(0.2, 0.07, 48, 24))

    # Reflectors inside the probe's 2 m cell (both reach 0.74 m at most from the probe,
    # leaving 0.26 m for the sandbox to move them), keeping the probe centre clear.
    mirror = b.material("mirror", (0.95, 0.95, 0.95))
    roots.append(b.node("sphere", mesh=b.mesh("sphere", sphere, mirror),
                        translation=(PROBE[0] - 0.42, PROBE[1], PROBE[2]),
                        extras={"specula_reflector": {"f0": 1.0}}))
    roots.append(b.node("torus", mesh=b.mesh("torus", ring, mirror),
                        translation=(PROBE[0] + 0.42, PROBE[1], PROBE[2]),
                        rotation=quat_axis((1, 0, 0), 60),
                        extras={"specula_reflector": True}))

    gltf = finish(b, roots, "room", "specula scripts/make_default_scene.py", "room.bin")
    return gltf, bytes(b.bin)


def write_scene(out_dir, stem, gltf, binary, textures=None):
    """Writes out_dir/stem.gltf, stem.bin and the textures (the glTF's buffer is stem.bin):
    `textures` as (name, pixel function, width, height), else the room's 64 x 64 ones."""
    os.makedirs(out_dir, exist_ok=True)
    for name, fn, w, h in textures or [(n, f, 64, 64) for n, f in TEXTURES]:
        write_png(os.path.join(out_dir, name), w, h, fn)
    with open(os.path.join(out_dir, stem + ".bin"), "wb") as f:
        f.write(binary)
    with open(os.path.join(out_dir, stem + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    total = sum(os.path.getsize(os.path.join(out_dir, n)) for n in os.listdir(out_dir))
    print("wrote %s (%d bytes in all)" % (out_dir, total), file=sys.stderr)


def main():
    gltf, binary = build()
    write_scene(OUT_DIR, "room", gltf, binary)


if __name__ == "__main__":
    main()
