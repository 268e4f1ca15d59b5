#!/usr/bin/env python3
"""Writes assets/room/room_camera_path.gltf: the default room (room.gltf, same room.bin) whose
camera node is animated (glTF animation 0, LINEAR): a 4 s dolly from x = -1.2 to +1.2 m along
the room's south side, turning to keep the reflectors (0, 1.2, 0) in view. The scene for the
PEM's camera path (specula-cook bake --path camera) and the loader's animation tests.

Usage: scripts/make_room_camera_path.py  (run from the repository root)"""
import base64
import json
import math
import struct

SRC, DST = "assets/room/room.gltf", "assets/room/room_camera_path.gltf"
TARGET = (0.0, 1.2, 0.0)
TIMES = [0.0, 1.0, 2.0, 3.0, 4.0]
EYES = [(x, 1.6, 3.48) for x in (-1.2, -0.6, 0.0, 0.6, 1.2)]


def look_rotation(eye, target):
    """The quaternion (x, y, z, w) turning -Z towards target, +Y up: yaw then pitch."""
    d = [t - e for t, e in zip(target, eye)]
    yaw = math.atan2(-d[0], -d[2])
    pitch = math.atan2(d[1], math.hypot(d[0], d[2]))
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    # q = q_yaw(about +Y) * q_pitch(about +X)
    return (cy * sp, sy * cp, -sy * sp, cy * cp)


def main():
    g = json.load(open(SRC))
    camera = next(i for i, n in enumerate(g["nodes"]) if "camera" in n)
    blob = b"".join(struct.pack("<f", t) for t in TIMES)
    blob += b"".join(struct.pack("<3f", *e) for e in EYES)
    blob += b"".join(struct.pack("<4f", *look_rotation(e, TARGET)) for e in EYES)
    buffer = len(g["buffers"])
    g["buffers"].append({"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," +
                                base64.b64encode(blob).decode()})
    n = len(TIMES)
    views = [(0, 4 * n), (4 * n, 12 * n), (16 * n, 16 * n)]
    first_view = len(g["bufferViews"])
    for offset, length in views:
        g["bufferViews"].append({"buffer": buffer, "byteOffset": offset, "byteLength": length})
    first = len(g["accessors"])
    g["accessors"] += [
        {"bufferView": first_view, "componentType": 5126, "count": n, "type": "SCALAR",
         "min": [TIMES[0]], "max": [TIMES[-1]]},
        {"bufferView": first_view + 1, "componentType": 5126, "count": n, "type": "VEC3"},
        {"bufferView": first_view + 2, "componentType": 5126, "count": n, "type": "VEC4"},
    ]
    g["nodes"][camera]["translation"] = list(EYES[0])
    g["nodes"][camera]["rotation"] = list(look_rotation(EYES[0], TARGET))
    g["animations"] = [{
        "name": "dolly",
        "samplers": [{"input": first, "output": first + 1, "interpolation": "LINEAR"},
                     {"input": first, "output": first + 2, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": camera, "path": "translation"}},
                     {"sampler": 1, "target": {"node": camera, "path": "rotation"}}],
    }]
    g["scenes"][0]["name"] = "room_camera_path"
    with open(DST, "w") as f:
        json.dump(g, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
