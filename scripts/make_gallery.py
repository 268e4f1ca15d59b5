#!/usr/bin/env python3
"""Writes a gallery hall with two mirror panels: assets/gallery/gallery.gltf + .bin + PNGs.

A test scene the effect plan was never tuned on: a long closed hall whose two rows of tall,
thin columns subtend small solid angles from the probe, and two flat free-standing mirrors
turned towards each other, so each reflects the columns and paintings and a bit of the
other. Standard library only; deterministic; geometry helpers, the glTF Builder and the PNG
writer from make_default_scene.py.

Layout (metres, right-handed, Y up, as glTF; "north" is -Z as in the default room):
  * the hall: inside x -7 .. 7, y 0 .. 4.5, z -3.5 .. 3.5 (14 x 4.5 x 7), closed: a floor
    (a checker of 0.875 m tiles), a ceiling and four walls, quads facing into the hall;
  * two rows of six round columns (radius 0.15, floor to ceiling, capped, each its own
    colour) at z -2.2 and z 2.2, at x -5.5, -3.3, -1.1, 1.1, 3.3, 5.5;
  * eight paintings: a textured canvas (a box 0.04 deep, its front 0.06 from the wall) in
    a dark frame (0.08 wider each side, 0.03 deep, 0.01 off the wall): 1.6 x 1.2 ones at
    x -4.4, 0 and 4.4 on the north and south walls (centres 1.7 up), a 2.4 x 1.8 one on the
    east wall (centre (7, 1.9, 0)) and on the west wall (centre (-7, 2.6, 0), above the
    mirrors as the camera sees them);
  * two mirror panels (boxes 1.0 wide, 1.8 tall, 0.04 thick, standing on the floor) 1.4 m
    apart: mirror_north at (0, 0.9, -0.7), mirror_south at (0, 0.9, 0.7), both facing +X
    (the camera) turned 25 degrees about Y towards each other (their fronts face
    (0.906, 0, +-0.423)), so they form a V open towards +X: inner edges at x -0.21,
    z +-0.25, outer edges at x 0.21, z +-1.15; each sees the other's front over about 4%
    of its cosine-weighted hemisphere;
  * the probe at (0, 1.0, 0), midway between the mirrors near their mid-height, 0.30 m in
    front of either mirror's mid-plane (0.31 m from the nearest mirror surface), with a 2 m
    cell (y 0 .. 2); the mirrors reach 1.16 m from it along Z, so they overhang that cell;
  * a perspective camera (yfov 0.6, 4:3) at (4.4, 1.6, 0.5), 4.47 m from the probe, in the
    aisle between the column rows, looking at the probe: the mirrors fill about 2/3 of the
    frame's width and height, the west end of the hall seen between and above them.
Nothing but the mirrors comes within 1 m of the probe (the floor is 1.0 m below it, the
nearest column 2.31 m away); everything lies inside the hall. Every object is its own root
node.
"""
import colorsys
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_default_scene as room  # noqa: E402  (Builder, geometry, PNG writer)
from make_bowl_room import check_winding  # noqa: E402
from make_two_rooms import look_at  # noqa: E402

ROOT = os.path.normpath(os.path.join(HERE, ".."))
OUT_DIR = os.path.join(ROOT, "assets", "gallery")

HALF_X, HALF_Z, HEIGHT = 7.0, 3.5, 4.5        # the hall's inside
COLUMN_RADIUS = 0.15
COLUMN_ROWS_Z = (-2.2, 2.2)
COLUMN_XS = (-5.5, -3.3, -1.1, 1.1, 3.3, 5.5)

MIRROR_SIZE = (1.0, 1.8, 0.04)                # width, height, thickness
MIRROR_GAP = 1.4                              # between the two mirrors' centres
MIRROR_TURN = 25.0                            # degrees, each towards the other
PROBE = (0.0, 1.0, 0.0)                       # the 2 m cell then spans y 0 .. 2
EYE = (4.4, 1.6, 0.5)
YFOV, ASPECT = 0.6, 4 / 3


# ---------------------------------------------------------------- textures
def floor_tiles(x, y):
    """128 x 64: 16 x 8 tiles of 8 pixels, 0.875 m on the 14 x 7 m floor."""
    if x % 8 == 0 or y % 8 == 0:
        return (120, 115, 105)
    return (215, 210, 195) if ((x // 8) + (y // 8)) % 2 == 0 else (75, 72, 80)


def stripes(x, y):
    band = ((x + y) // 12) % 4
    return [(220, 60, 40), (240, 200, 40), (40, 120, 220), (240, 240, 240)][band]


def grid(x, y):
    line = x % 16 in (0, 1) or y % 16 in (0, 1)
    return (30, 30, 30) if line else (90, 190, 120)


def rings(x, y):
    r = math.hypot(x - 63.5, y - 47.5)
    return [(200, 30, 60), (250, 245, 230), (30, 40, 120), (250, 245, 230)][int(r // 7) % 4]


def dots(x, y):
    cx, cy = (x // 16) * 16 + 8, (y // 16) * 16 + 8
    if (x - cx) ** 2 + (y - cy) ** 2 <= 25:
        return [(230, 90, 20), (20, 150, 160)][((x // 16) + (y // 16)) % 2]
    return (245, 235, 205)


MONDRIAN = [  # x0, y0, x1, y1 (pixels, inclusive .. exclusive), colour
    (0, 0, 40, 56, (220, 30, 30)), (88, 60, 128, 96, (30, 60, 180)),
    (40, 80, 88, 96, (245, 210, 30)), (104, 0, 128, 28, (245, 210, 30)),
    (0, 72, 40, 96, (20, 20, 20))]


def mondrian(x, y):
    if x in (40, 41, 88, 89) or y in (56, 57, 80, 81) or (x >= 104 and y in (28, 29)) or \
            (x in (104, 105) and y < 28):
        return (15, 15, 15)
    for x0, y0, x1, y1, c in MONDRIAN:
        if x0 <= x < x1 and y0 <= y < y1:
            return c
    return (240, 238, 228)


BARS = [3, 1, 2, 5, 1, 1, 4, 2, 6, 1, 3, 2, 1, 5, 2, 2, 7, 1, 2, 3, 1, 4, 1, 2, 6, 3, 1, 2]


def bars(x, y):
    """Vertical bars of uneven widths, like a bar code; the lowest sixth a hue ramp."""
    if y >= 80:
        r, g, b = colorsys.hsv_to_rgb(x / 128, 0.9, 0.9)
        return (int(r * 255), int(g * 255), int(b * 255))
    edge, i = 0, 0
    while True:
        edge += BARS[i % len(BARS)] * 2
        if x < edge:
            return (20, 20, 25) if i % 2 == 0 else (235, 235, 225)
        i += 1


def hues(x, y):
    """8 hue columns x 6 value rows."""
    r, g, b = colorsys.hsv_to_rgb((x // 16) / 8, 0.85, 1.0 - (y // 16) / 7)
    return (int(r * 255), int(g * 255), int(b * 255))


def landscape(x, y):
    """Sky, sun and two rows of hills."""
    if (x - 96) ** 2 + (y - 22) ** 2 <= 100:
        return (250, 215, 70)
    if y > 62 + 8 * math.sin(x / 11.0):
        return (50, 120, 45)
    if y > 50 + 10 * math.sin(x / 17.0 + 1.0):
        return (110, 150, 170)
    t = y / 60
    return (int(70 + 130 * t), int(120 + 100 * t), int(210 + 30 * t))


TEXTURES = [  # name, pixel function, width, height
    ("floor_tiles.png", floor_tiles, 128, 64),
    ("painting_stripes.png", stripes, 128, 96),
    ("painting_grid.png", grid, 128, 96),
    ("painting_rings.png", rings, 128, 96),
    ("painting_dots.png", dots, 128, 96),
    ("painting_mondrian.png", mondrian, 128, 96),
    ("painting_bars.png", bars, 128, 96),
    ("painting_hues.png", hues, 128, 96),
    ("painting_landscape.png", landscape, 128, 96)]
TEX = {name[:-4]: i for i, (name, _, _, _) in enumerate(TEXTURES)}

PAINTINGS = [  # name, wall point (canvas centre on the wall), yaw (front faces into the hall),
    #            canvas width, height, texture
    ("painting_north_west", (-4.4, 1.7, -HALF_Z), 0, 1.6, 1.2, "painting_stripes"),
    ("painting_north_middle", (0.0, 1.7, -HALF_Z), 0, 1.6, 1.2, "painting_rings"),
    ("painting_north_east", (4.4, 1.7, -HALF_Z), 0, 1.6, 1.2, "painting_grid"),
    ("painting_south_west", (-4.4, 1.7, HALF_Z), 180, 1.6, 1.2, "painting_dots"),
    ("painting_south_middle", (0.0, 1.7, HALF_Z), 180, 1.6, 1.2, "painting_mondrian"),
    ("painting_south_east", (4.4, 1.7, HALF_Z), 180, 1.6, 1.2, "painting_bars"),
    ("painting_east", (HALF_X, 1.9, 0.0), -90, 2.4, 1.8, "painting_hues"),
    ("painting_west", (-HALF_X, 2.6, 0.0), 90, 2.4, 1.8, "painting_landscape")]


# ---------------------------------------------------------------- geometry
def cylinder(radius, height, segments):
    """A capped cylinder about the Y axis from y = 0 to y = height: the side (radial
    normals) and the two caps (normals -Y and +Y)."""
    pos, nrm, uv, idx = [], [], [], []
    for s in range(segments + 1):
        phi = 2 * math.pi * s / segments
        c, sn = math.cos(phi), -math.sin(phi)
        pos += [(radius * c, 0.0, radius * sn), (radius * c, height, radius * sn)]
        nrm += [(c, 0.0, sn)] * 2
        uv += [(s / segments, 1.0), (s / segments, 0.0)]
    for s in range(segments):
        b0, t0, b1, t1 = 2 * s, 2 * s + 1, 2 * s + 2, 2 * s + 3
        idx += [b0, b1, t1, b0, t1, t0]
    for y, ny in ((0.0, -1.0), (height, 1.0)):
        centre = len(pos)
        pos.append((0.0, y, 0.0))
        nrm.append((0.0, ny, 0.0))
        uv.append((0.5, 0.5))
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            c, sn = math.cos(phi), -math.sin(phi)
            pos.append((radius * c, y, radius * sn))
            nrm.append((0.0, ny, 0.0))
            uv.append((0.5 + 0.5 * c, 0.5 - 0.5 * sn))
        for s in range(segments):
            a, b = centre + 1 + s, centre + 1 + (s + 1) % segments
            idx += [centre, a, b] if ny > 0 else [centre, b, a]
    return pos, nrm, uv, idx


# ---------------------------------------------------------------- helpers
def yaw(degrees):
    return room.quat_axis((0, 1, 0), degrees)


# ---------------------------------------------------------------- scene
def build():
    b = room.Builder()
    quad = b.geometry(room.unit_quad())
    box = b.geometry(room.unit_box())
    column_geom = cylinder(COLUMN_RADIUS, HEIGHT, 32)
    check_winding(column_geom)
    column = b.geometry(column_geom)
    roots = []

    # Floor, ceiling and walls: the unit quad faces +Z; each is turned to face into the hall.
    floor = b.material("floor", (0.9, 0.9, 0.9), TEX["floor_tiles"])
    roots.append(b.node("floor", mesh=b.mesh("floor", quad, floor),
                        rotation=room.quat_axis((1, 0, 0), -90),
                        scale=(2 * HALF_X, 2 * HALF_Z, 1)))
    ceiling = b.material("ceiling", (0.88, 0.87, 0.84))
    roots.append(b.node("ceiling", mesh=b.mesh("ceiling", quad, ceiling),
                        translation=(0, HEIGHT, 0), rotation=room.quat_axis((1, 0, 0), 90),
                        scale=(2 * HALF_X, 2 * HALF_Z, 1)))
    walls = [("wall_north", (0, HEIGHT / 2, -HALF_Z), 0, 2 * HALF_X, (0.78, 0.72, 0.60)),
             ("wall_south", (0, HEIGHT / 2, HALF_Z), 180, 2 * HALF_X, (0.56, 0.64, 0.76)),
             ("wall_east", (HALF_X, HEIGHT / 2, 0), -90, 2 * HALF_Z, (0.66, 0.76, 0.56)),
             ("wall_west", (-HALF_X, HEIGHT / 2, 0), 90, 2 * HALF_Z, (0.76, 0.58, 0.66))]
    for name, t, turn, width, color in walls:
        mat = b.material(name, color)
        roots.append(b.node(name, mesh=b.mesh(name, quad, mat), translation=t,
                            rotation=yaw(turn), scale=(width, HEIGHT, 1)))

    # Columns: two rows along X, each column its own hue (north row first, west to east).
    k = 0
    for row, z in zip(("north", "south"), COLUMN_ROWS_Z):
        for i, x in enumerate(COLUMN_XS):
            r, g, bl = colorsys.hsv_to_rgb(k / (2 * len(COLUMN_XS)), 0.8, 0.85)
            k += 1
            name = "column_%s_%d" % (row, i)
            mat = b.material(name, (round(r, 3), round(g, 3), round(bl, 3)))
            roots.append(b.node(name, mesh=b.mesh(name, column, mat), translation=(x, 0, z)))

    # Paintings: a canvas in a frame, placed in the frame of their wall point (local +Z
    # into the hall).
    frame = b.material("painting_frame", (0.12, 0.08, 0.05))
    for name, at, turn, w, h, tex in PAINTINGS:
        canvas = b.material(name, (1, 1, 1), TEX[tex])
        children = [
            b.node(name + "_frame", mesh=b.mesh(name + "_frame", box, frame),
                   translation=(0, 0, 0.025), scale=(w + 0.16, h + 0.16, 0.03)),
            b.node(name + "_canvas", mesh=b.mesh(name + "_canvas", box, canvas),
                   translation=(0, 0, 0.04), scale=(w, h, 0.04))]
        roots.append(b.node(name, translation=at, rotation=yaw(turn), children=children))

    # The mirrors: both face +X (yaw 90 turns the box's +Z front there), turned towards
    # each other.
    mirror = b.material("mirror", (0.95, 0.95, 0.95))
    for name, dz, turn in (("mirror_north", -MIRROR_GAP / 2, 90 - MIRROR_TURN),
                           ("mirror_south", MIRROR_GAP / 2, 90 + MIRROR_TURN)):
        roots.append(b.node(name, mesh=b.mesh(name, box, mirror),
                            translation=(PROBE[0], MIRROR_SIZE[1] / 2, PROBE[2] + dz),
                            rotation=yaw(turn), scale=MIRROR_SIZE,
                            extras={"specula_reflector": {"f0": 1.0}}))

    roots.append(b.node("probe", translation=PROBE, extras={"specula_probe": {"cell_size": 2.0}}))
    roots.append(b.node("camera", camera=0, translation=EYE, rotation=look_at(EYE, PROBE)))

    gltf = {
        "asset": {"version": "2.0", "generator": "specula scripts/make_gallery.py"},
        "scene": 0,
        "scenes": [{"name": "gallery", "nodes": roots}],
        "nodes": b.nodes,
        "meshes": b.meshes,
        "materials": b.materials,
        "textures": [{"sampler": 0, "source": i} for i in range(len(TEXTURES))],
        "images": [{"uri": name, "name": name} for name, _, _, _ in TEXTURES],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "cameras": [{"type": "perspective", "name": "camera",
                     "perspective": {"yfov": YFOV, "aspectRatio": ASPECT, "znear": 0.05,
                                     "zfar": 100.0}}],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"uri": "gallery.bin", "byteLength": len(b.bin)}],
    }
    return gltf, bytes(b.bin)


def main():
    gltf, binary = build()
    room.write_scene(OUT_DIR, "gallery", gltf, binary, TEXTURES)


if __name__ == "__main__":
    main()
