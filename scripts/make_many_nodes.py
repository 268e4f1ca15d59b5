#!/usr/bin/env python3
"""Writes a scene of many nodes for the big-scene bench (issue 34): the default room
(make_default_scene.py: walls, columns, panels, table, the two mirrors and the probe) with N
small boxes scattered through it, each its own root node, as a level designer's clutter.

  scripts/make_many_nodes.py N OUT_DIR      writes OUT_DIR/many_N.gltf + .bin + textures

The boxes (0.05 .. 0.25 m) lie inside the room (x, z in -3.8 .. 3.8, y in 0.1 .. 3.8) but
outside a 1.2 m sphere about the probe, so some are near enough for parallax and many overlap
as seen from the reflectors' cell: the case where one object layer per node would exceed the
runtime's layer cap. Every box shares one mesh and one of eight materials. Standard library
only; deterministic (a fixed seed)."""
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_default_scene as room  # noqa: E402  (Builder, geometry, writer)


def build(count):
    b = room.Builder()
    roots = room.build_room(b)
    sphere = b.geometry(room.uv_sphere(0.32, 32, 32))
    box = b.geometry(room.unit_box())
    mirror = b.material("mirror", (0.95, 0.95, 0.95))
    probe = room.PROBE
    roots.append(b.node("sphere", mesh=b.mesh("sphere", sphere, mirror),
                        translation=(probe[0] - 0.42, probe[1], probe[2]),
                        extras={"specula_reflector": True}))
    rng = random.Random(34)
    colours = [(0.8, 0.2, 0.1), (0.1, 0.6, 0.2), (0.1, 0.2, 0.8), (0.9, 0.8, 0.1),
               (0.6, 0.1, 0.7), (0.1, 0.7, 0.7), (0.9, 0.5, 0.1), (0.5, 0.5, 0.5)]
    meshes = [b.mesh("clutter_%d" % i, box, b.material("clutter_%d" % i, c))
              for i, c in enumerate(colours)]
    for i in range(count):
        while True:
            p = (rng.uniform(-3.8, 3.8), rng.uniform(0.1, 3.8), rng.uniform(-3.8, 3.8))
            if sum((p[k] - probe[k]) ** 2 for k in range(3)) > 1.2 ** 2:
                break
        s = rng.uniform(0.05, 0.25)
        roots.append(b.node("box_%d" % i, mesh=meshes[i % len(meshes)], translation=p,
                            scale=(s, s, s)))
    gltf = room.finish(b, roots, "many_%d" % count, "specula scripts/make_many_nodes.py",
                       "many_%d.bin" % count)
    return gltf, bytes(b.bin)


def main(argv):
    if len(argv) != 3 or not argv[1].isdigit():
        print(__doc__, file=sys.stderr)
        return 2
    count = int(argv[1])
    gltf, binary = build(count)
    room.write_scene(argv[2], "many_%d" % count, gltf, binary)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
