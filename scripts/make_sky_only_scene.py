#!/usr/bin/env python3
"""Writes assets/sky_only/sky_only.gltf: a mirror sphere under the open sky, nothing else.

The canonical scene whose effect plan must be the classic environment map (the issue's
"distant sky only"): there is no near geometry, so any correction would be paid for nothing.
Standard library only; geometry helpers from make_default_scene.py.
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_default_scene as room  # noqa: E402

OUT_DIR = os.path.join(HERE, "..", "assets", "sky_only")
PROBE = (0.0, 1.2, 0.0)


def build():
    b = room.Builder()
    mirror = b.material("mirror", (0.9, 0.9, 0.9))
    sphere = b.mesh("sphere", b.geometry(room.uv_sphere(0.5, 48, 24)), mirror)
    roots = [
        b.node("sphere", mesh=sphere, translation=PROBE, extras={"specula_reflector": True}),
        b.node("probe", translation=PROBE, extras={"specula_probe": {"cell_size": 1.5}}),
    ]
    eye = (0.0, 1.6, 3.5)
    pitch = math.degrees(math.atan2(PROBE[1] - eye[1], math.hypot(eye[0], eye[2])))
    roots.append(b.node("camera", camera=0, translation=eye,
                        rotation=room.quat_axis((1, 0, 0), pitch)))
    gltf = {
        "asset": {"version": "2.0", "generator": "specula scripts/make_sky_only_scene.py"},
        "scene": 0,
        "scenes": [{"name": "sky_only", "nodes": roots}],
        "nodes": b.nodes,
        "meshes": b.meshes,
        "materials": b.materials,
        "cameras": [{"type": "perspective", "name": "camera",
                     "perspective": {"yfov": 0.9, "aspectRatio": 4 / 3, "znear": 0.05,
                                     "zfar": 100.0}}],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"uri": "sky_only.bin", "byteLength": len(b.bin)}],
    }
    return gltf, bytes(b.bin)


def main():
    os.makedirs(OUT_DIR, exist_ok=True)
    gltf, binary = build()
    with open(os.path.join(OUT_DIR, "sky_only.bin"), "wb") as f:
        f.write(binary)
    with open(os.path.join(OUT_DIR, "sky_only.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
