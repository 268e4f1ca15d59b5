#!/usr/bin/env python3
"""Writes a bench scene with a concave mirror: assets/bowl_room/bowl_room.gltf + .bin + PNGs.

The default room (make_default_scene.py: same floor, walls, columns, panels, table, probe
and camera) with other reflectors: a mirror bowl, whose concave inside reflects itself, and
a small mirror sphere that the bowl's inside reflects. What a probe cannot represent -
mirrors seeing mirrors - is then a large part of the picture, not a thin rim. Standard
library only; deterministic.

Layout (metres, right-handed, Y up, as glTF):
  * the default room, the probe at (0, 1.2, 0) with a 2 m cell, the camera 3.5 m away on +Z;
  * the bowl: a hemispherical shell, inner radius 0.45, wall 0.03 thick (outer radius
    0.48), made of its inner surface (normals towards the centre), its outer surface
    (normals away from it) and the flat rim ring between them (normals out of the
    opening); the centre of its sphere sits 0.05 below the probe, the opening turned 35
    degrees from straight up towards the camera, so the camera looks into it;
  * the sphere: radius 0.15, above the opening and to the camera's right, 0.19 m clear of
    the rim plane, where the bowl's inside reflects it.
Both reflectors lie within 0.53 m of the probe along every axis (the bowl's bottom is the
farthest), 0.47 m inside the cell; nothing else comes within 2 m of the probe.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_default_scene as room  # noqa: E402  (room, Builder, geometry, PNG writer)

ROOT = os.path.normpath(os.path.join(HERE, ".."))
OUT_DIR = os.path.join(ROOT, "assets", "bowl_room")
PROBE = room.PROBE

INNER, WALL = 0.45, 0.03
TILT = 35.0  # degrees from straight up towards +Z (the camera)
BOWL_CENTRE = (PROBE[0], PROBE[1] - 0.05, PROBE[2])
SPHERE_RADIUS = 0.15
# In the bowl's frame (opening +Y): 0.34 above the rim plane, off the axis to +X.
SPHERE_LOCAL = (0.2, 0.34, 0.05)


def hemisphere(radius, segments, rings, inward):
    """The lower half (y <= 0) of a sphere about the origin, rim on y = 0. Normals point
    away from the centre, or towards it when `inward` (then the winding is reversed too,
    so triangles stay counter-clockwise seen from the side their normals point to)."""
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        theta = math.pi / 2 + (math.pi / 2) * r / rings  # equator .. bottom pole
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            pos.append(tuple(radius * c for c in n))
            nrm.append(tuple(-c for c in n) if inward else n)
            uv.append((s / segments, r / rings))
    row = segments + 1
    for r in range(rings):
        for s in range(segments):
            a, b = r * row + s, r * row + s + 1
            c, d = (r + 1) * row + s, (r + 1) * row + s + 1
            tris = [(a, c, b)]
            if r != rings - 1:  # the last row's second triangle would be degenerate
                tris.append((b, c, d))
            for t in tris:
                idx += [t[0], t[2], t[1]] if inward else list(t)
    return pos, nrm, uv, idx


def rim_ring(inner, outer, segments):
    """The flat ring inner <= |xz| <= outer on y = 0, facing +Y."""
    pos, nrm, uv, idx = [], [], [], []
    for s in range(segments + 1):
        phi = 2 * math.pi * s / segments
        c, sn = math.cos(phi), -math.sin(phi)
        pos += [(inner * c, 0.0, inner * sn), (outer * c, 0.0, outer * sn)]
        nrm += [(0.0, 1.0, 0.0)] * 2
        uv += [(s / segments, 0.0), (s / segments, 1.0)]
    for s in range(segments):
        i0, o0, i1, o1 = 2 * s, 2 * s + 1, 2 * s + 2, 2 * s + 3
        idx += [i0, o0, o1, i0, o1, i1]
    return pos, nrm, uv, idx


def merge(*geoms):
    pos, nrm, uv, idx = [], [], [], []
    for p, n, u, i in geoms:
        base = len(pos)
        pos += p
        nrm += n
        uv += u
        idx += [base + k for k in i]
    return pos, nrm, uv, idx


def check_winding(geom):
    """Every triangle counter-clockwise seen from where its vertex normals point."""
    pos, nrm, _, idx = geom
    for k in range(0, len(idx), 3):
        a, b, c = (pos[i] for i in idx[k:k + 3])
        e1 = [b[i] - a[i] for i in range(3)]
        e2 = [c[i] - a[i] for i in range(3)]
        g = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0])
        area = math.sqrt(sum(x * x for x in g))
        assert area > 1e-9, "degenerate triangle %d" % (k // 3)
        n = [sum(nrm[i][j] for i in idx[k:k + 3]) for j in range(3)]
        assert sum(g[j] * n[j] for j in range(3)) > 0, "triangle %d winds backwards" % (k // 3)


def bowl():
    outer = INNER + WALL
    geom = merge(hemisphere(INNER, 64, 16, inward=True), hemisphere(outer, 64, 16, inward=False),
                 rim_ring(INNER, outer, 64))
    check_winding(geom)
    return geom


def build():
    b = room.Builder()
    roots = room.build_room(b)
    mirror = b.material("mirror", (0.95, 0.95, 0.95))

    tilt = room.quat_axis((1, 0, 0), TILT)  # turns +Y (the opening) towards +Z
    roots.append(b.node("bowl", mesh=b.mesh("bowl", b.geometry(bowl()), mirror),
                        translation=BOWL_CENTRE, rotation=tilt,
                        extras={"specula_reflector": {"f0": 1.0}}))

    # The sphere's place, given in the bowl's frame, turned with it.
    a = math.radians(TILT)
    x, y, z = SPHERE_LOCAL
    at = (BOWL_CENTRE[0] + x, BOWL_CENTRE[1] + y * math.cos(a) - z * math.sin(a),
          BOWL_CENTRE[2] + y * math.sin(a) + z * math.cos(a))
    sphere = b.geometry(room.uv_sphere(SPHERE_RADIUS, 32, 16))
    roots.append(b.node("sphere", mesh=b.mesh("sphere", sphere, mirror), translation=at,
                        extras={"specula_reflector": True}))

    gltf = room.finish(b, roots, "bowl_room", "specula scripts/make_bowl_room.py",
                       "bowl_room.bin")
    return gltf, bytes(b.bin)


def main():
    gltf, binary = build()
    room.write_scene(OUT_DIR, "bowl_room", gltf, binary)


if __name__ == "__main__":
    main()
