#!/usr/bin/env python3
"""Writes a two-probe scene: assets/two_rooms/two_rooms.gltf + .bin + small PNG textures.

Two closed box rooms side by side along X, joined by a doorway in the wall they share, each
in its own colour family (A warm red/orange, B cool blue/green) and each with one probe, for
the probe-leak tests (what a probe in A shows of B must come through the doorway) and the
transition tests (a reflector walked from A to B through the doorway, where the two probes'
influences overlap). Standard library only; deterministic; geometry helpers, the glTF
Builder and the PNG writer from make_default_scene.py.

Layout (metres, right-handed, Y up, as glTF; "north" is -Z as in the default room):
  * every wall, floor and ceiling is a closed box 0.1 m thick (walls run 0.1 below the
    floor's top to 0.1 above the ceiling's underside), so nothing outside a room is seen
    from inside it except through the doorway; nothing is open to the sky;
  * room A: inside x -5.95 .. -0.05, y 0 .. 3, z -2.95 .. 2.95 (5.9 x 3 x 5.9);
    room B: inside x 0.05 .. 5.95, same y and z; the shared wall is x -0.05 .. 0.05, its
    A-facing half (x < 0) in A's colours, its B-facing half (x > 0) in B's;
  * the doorway: z -0.6 .. 0.6, y 0 .. 2.2 (1.2 wide, 2.2 high), centred in the shared wall;
  * floors (a tinted checker, 8 x 8 tiles of about 0.75 m) and ceilings per room; a textured
    panel 2 cm in front of A's west wall and of B's east wall (B's faces the doorway);
  * room A: an amber column (0.3 x 3 x 0.3) at (-4.6, -1.8) [x, z], a table (top 0.75 high)
    at (-3.2, 1.9), a crate (0.5 cube) at (-1.6, -1.8);
    room B: a teal column at (4.2, -0.8) (seen through the doorway), a table at (3.5, -2.0),
    a crate at (1.6, 1.8);
  * probes at the rooms' centres, 1.2 m up: room_a_probe (-3, 1.2, 0), room_b_probe
    (3, 1.2, 0), A's first; each "specula_probe" has cell_size 2, blend_distance 0.5,
    priority 0, and probe-relative boxes: proxy = the room's inside box, influence = the same
    box reaching 0.5 m past the shared wall into the other room (A's to x 0.55, B's from
    x -0.55), so the influences overlap over x -0.55 .. 0.55 around the doorway;
  * a mirror sphere (r 0.3, "specula_reflector": true) in A near the doorway at
    (-1, 1.2, 0), 0.65 m clear of the shared wall (outside A's 2 m cell, which spans x -4 .. -2);
  * a perspective camera in A at (-4.5, 1.6, 0.3) looking at the sphere's centre, 1.5 m
    behind A's probe (so the walk's orbit about the probe keeps the sphere in view), with the
    doorway, B's column and B's panel seen behind the sphere.
Every object is its own root node (its own probe layer).
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_default_scene as room  # noqa: E402  (Builder, geometry, PNG writer)

ROOT = os.path.normpath(os.path.join(HERE, ".."))
OUT_DIR = os.path.join(ROOT, "assets", "two_rooms")

T = 0.1            # wall, floor and ceiling thickness
HALF = 6.0         # each room is 6 m between its wall centres along X and Z
HEIGHT = 3.0       # floor top to ceiling underside
DOOR_W, DOOR_H = 1.2, 2.2
REACH = 0.5        # how far an influence reaches into the other room past the shared wall
PROBE_Y = 1.2

# Inside boxes (world), min and max corners.
ROOM_A = ((-HALF + T / 2, 0.0, -HALF / 2 + T / 2), (-T / 2, HEIGHT, HALF / 2 - T / 2))
ROOM_B = ((T / 2, 0.0, -HALF / 2 + T / 2), (HALF - T / 2, HEIGHT, HALF / 2 - T / 2))
PROBE_A = (-HALF / 2, PROBE_Y, 0.0)
PROBE_B = (HALF / 2, PROBE_Y, 0.0)
SPHERE_RADIUS = 0.3
SPHERE = (-1.0, PROBE_Y, 0.0)
EYE = (-4.5, 1.6, 0.3)

WARM = {"wall_west": (0.85, 0.42, 0.18), "wall_north": (0.80, 0.22, 0.14),
        "wall_south": (0.90, 0.55, 0.30), "doorway_wall": (0.72, 0.16, 0.20),
        "floor": (0.75, 0.50, 0.36), "ceiling": (0.96, 0.84, 0.70)}
COOL = {"wall_east": (0.18, 0.38, 0.85), "wall_north": (0.14, 0.60, 0.52),
        "wall_south": (0.30, 0.55, 0.90), "doorway_wall": (0.16, 0.66, 0.34),
        "floor": (0.40, 0.55, 0.70), "ceiling": (0.72, 0.88, 0.94)}


# ---------------------------------------------------------------- textures
def tiles(x, y):
    """Neutral checker, tinted per room by the floor material."""
    return (235, 235, 235) if ((x // 8) + (y // 8)) % 2 == 0 else (110, 110, 110)


def warm_stripes(x, y):
    band = ((x + y) // 8) % 4
    return [(200, 40, 30), (245, 170, 40), (150, 60, 20), (250, 225, 190)][band]


def cool_grid(x, y):
    line = x % 16 in (0, 1) or y % 16 in (0, 1)
    return (20, 40, 110) if line else (90, 200, 190)


TEXTURES = [("floor_tiles.png", tiles), ("panel_warm.png", warm_stripes),
            ("panel_cool.png", cool_grid)]
TEX_FLOOR, TEX_WARM, TEX_COOL = 0, 1, 2


# ---------------------------------------------------------------- helpers
def qmul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def look_at(eye, target):
    """Rotation turning a glTF camera (looking down its -Z, +Y up) at `target`."""
    d = [target[i] - eye[i] for i in range(3)]
    yaw = math.degrees(math.atan2(-d[0], -d[2]))
    pitch = math.degrees(math.atan2(d[1], math.hypot(d[0], d[2])))
    return qmul(room.quat_axis((0, 1, 0), yaw), room.quat_axis((1, 0, 0), pitch))


def sub(a, b):
    return [round(a[i] - b[i], 6) for i in range(3)]


def probe_markup(inside, probe, towards_other):
    """Probe-relative proxy (the room's inside) and influence (reaching REACH past the
    shared wall, whose far face is T beyond the room's inside face)."""
    lo, hi = list(inside[0]), list(inside[1])
    ilo, ihi = list(lo), list(hi)
    if towards_other > 0:
        ihi[0] += T + REACH
    else:
        ilo[0] -= T + REACH
    return {"cell_size": 2.0,
            "proxy": {"min": sub(lo, probe), "max": sub(hi, probe)},
            "influence": {"box": {"min": sub(ilo, probe), "max": sub(ihi, probe)}},
            "blend_distance": 0.5, "priority": 0}


class Scene:
    def __init__(self):
        self.b = room.Builder()
        self.box = self.b.geometry(room.unit_box())
        self.quad = self.b.geometry(room.unit_quad())
        self.roots = []

    def box_node(self, name, lo, hi, material):
        """A node of the unit box stretched over the world box lo .. hi."""
        centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
        size = [hi[i] - lo[i] for i in range(3)]
        return self.b.node(name, mesh=self.b.mesh(name, self.box, material), translation=centre,
                           scale=size)

    def add_box(self, name, lo, hi, color, texture=None):
        self.roots.append(self.box_node(name, lo, hi, self.b.material(name, color, texture)))

    def add_group(self, name, parts, color):
        mat = self.b.material(name, color)
        children = [self.box_node("%s_%s" % (name, part), lo, hi, mat) for part, lo, hi in parts]
        self.roots.append(self.b.node(name, children=children))

    def room(self, tag, side, colors, inside, panel_texture):
        """The shell of one room: side -1 is A (x < 0), +1 is B (x > 0)."""
        (x0, y0, z0), (x1, y1, z1) = inside
        # The room's extent to the shared wall's mid-plane x = 0 and over its outer walls.
        xa, xb = (x0 - T, 0.0) if side < 0 else (0.0, x1 + T)
        zlo, zhi, ylo, yhi = z0 - T, z1 + T, y0 - T, y1 + T
        p = "room_%s_" % tag
        self.add_box(p + "floor", (xa, ylo, zlo), (xb, y0, zhi), colors["floor"], TEX_FLOOR)
        self.add_box(p + "ceiling", (xa, y1, zlo), (xb, yhi, zhi), colors["ceiling"])
        self.add_box(p + "wall_north", (xa, ylo, zlo), (xb, yhi, z0), colors["wall_north"])
        self.add_box(p + "wall_south", (xa, ylo, z1), (xb, yhi, zhi), colors["wall_south"])
        if side < 0:
            self.add_box(p + "wall_west", (xa, ylo, z0), (x0, yhi, z1), colors["wall_west"])
        else:
            self.add_box(p + "wall_east", (x1, ylo, z0), (xb, yhi, z1), colors["wall_east"])
        # This room's half of the shared wall, around the doorway: two jambs and a lintel.
        wa, wb = (-T / 2, 0.0) if side < 0 else (0.0, T / 2)
        d = DOOR_W / 2
        self.add_group(p + "doorway_wall", [
            ("north", (wa, ylo, zlo), (wb, yhi, -d)),
            ("south", (wa, ylo, d), (wb, yhi, zhi)),
            ("lintel", (wa, DOOR_H, -d), (wb, yhi, d))], colors["doorway_wall"])
        # A textured panel 2 cm in front of the far wall, facing into the room.
        far = (x0 + 0.02) if side < 0 else (x1 - 0.02)
        name = p + "panel"
        mat = self.b.material(name, (1, 1, 1), panel_texture)
        self.roots.append(self.b.node(name, mesh=self.b.mesh(name, self.quad, mat),
                                      translation=(far, 1.6, 0.0),
                                      rotation=room.quat_axis((0, 1, 0), -90 * side),
                                      scale=(2.0, 1.2, 1)))

    def table(self, name, at, color):
        mat = self.b.material(name, color)
        top = self.b.mesh(name + "_top", self.box, mat)
        leg = self.b.mesh(name + "_leg", self.box, mat)
        children = [self.b.node(name + "_top", mesh=top, translation=(0, 0.75, 0),
                                scale=(1.4, 0.06, 0.8))]
        for i, (x, z) in enumerate(((-0.62, -0.33), (0.62, -0.33), (0.62, 0.33), (-0.62, 0.33))):
            children.append(self.b.node("%s_leg_%d" % (name, i), mesh=leg,
                                        translation=(x, 0.36, z), scale=(0.06, 0.72, 0.06)))
        self.roots.append(self.b.node(name, translation=at, children=children))

    def column(self, name, x, z, color):
        self.add_box(name, (x - 0.15, 0.0, z - 0.15), (x + 0.15, HEIGHT, z + 0.15), color)

    def crate(self, name, x, z, color):
        self.add_box(name, (x - 0.25, 0.0, z - 0.25), (x + 0.25, 0.5, z + 0.25), color)


def build():
    s = Scene()
    s.room("a", -1, WARM, ROOM_A, TEX_WARM)
    s.room("b", +1, COOL, ROOM_B, TEX_COOL)
    s.column("room_a_column", -4.6, -1.8, (0.95, 0.70, 0.10))
    s.table("room_a_table", (-3.2, 0.0, 1.9), (0.50, 0.22, 0.12))
    s.crate("room_a_crate", -1.6, -1.8, (0.85, 0.45, 0.35))
    s.column("room_b_column", 4.2, -0.8, (0.10, 0.75, 0.70))
    s.table("room_b_table", (3.5, 0.0, -2.0), (0.12, 0.22, 0.50))
    s.crate("room_b_crate", 1.6, 1.8, (0.35, 0.75, 0.55))

    b = s.b
    mirror = b.material("mirror", (0.95, 0.95, 0.95))
    sphere = b.geometry(room.uv_sphere(SPHERE_RADIUS, 48, 24))
    s.roots.append(b.node("mirror_sphere", mesh=b.mesh("mirror_sphere", sphere, mirror),
                          translation=SPHERE, extras={"specula_reflector": True}))

    # Room A's probe first: tools reading one probe take the first.
    s.roots.append(b.node("room_a_probe", translation=PROBE_A,
                          extras={"specula_probe": probe_markup(ROOM_A, PROBE_A, +1)}))
    s.roots.append(b.node("room_b_probe", translation=PROBE_B,
                          extras={"specula_probe": probe_markup(ROOM_B, PROBE_B, -1)}))
    s.roots.append(b.node("camera", camera=0, translation=EYE, rotation=look_at(EYE, SPHERE)))

    gltf = {
        "asset": {"version": "2.0", "generator": "specula scripts/make_two_rooms.py"},
        "scene": 0,
        "scenes": [{"name": "two_rooms", "nodes": s.roots}],
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
        "buffers": [{"uri": "two_rooms.bin", "byteLength": len(b.bin)}],
    }
    return gltf, bytes(b.bin)


def main():
    gltf, binary = build()
    os.makedirs(OUT_DIR, exist_ok=True)
    for name, fn in TEXTURES:
        room.write_png(os.path.join(OUT_DIR, name), 64, 64, fn)
    with open(os.path.join(OUT_DIR, "two_rooms.bin"), "wb") as f:
        f.write(binary)
    with open(os.path.join(OUT_DIR, "two_rooms.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    total = sum(os.path.getsize(os.path.join(OUT_DIR, n)) for n in os.listdir(OUT_DIR))
    print("wrote %s (%d bytes in all)" % (OUT_DIR, total), file=sys.stderr)


if __name__ == "__main__":
    main()
