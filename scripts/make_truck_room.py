#!/usr/bin/env python3
"""Writes the sandbox's second bench scene: assets/truck_room/truck_room.gltf + .bin + floor.png.

Built from the third-party assets in assets/scenes/ (copies of ../shared/scenes/): the Cesium
milk truck is the mirror reflector (the seeds use a car), three Khronos ducks stand in a
room with six columns as near environment objects. The foreign meshes, their buffers and
their textures are merged into one self-contained glTF (the PNGs go into the .bin as buffer
views), so the scene needs no files outside its folder. Standard library only; the room's
geometry helpers come from make_default_scene.py.

Layout (metres, right-handed, Y up):
  * room 9 x 9 x 4 centred at the origin, floor at y = 0, open to the sky;
  * six 0.35 m square, 2.8 m tall columns on a ring of radius 3 m, none within 30 degrees
    of the camera's line to the probe (the sandbox's walk swings the camera by 23);
  * three ducks (about 0.9 m tall) on the floor between the columns, 2.9-3.3 m away;
  * the milk truck, scaled to 1.46 m long, centred on the probe at (0, 1.0, 0), turned 30
    degrees; the probe's cell is 1.8 m (the truck fits; its floor side stays 0.1 m above the
    floor); a camera 3.6 m away looks at it.
"""
import json
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_default_scene as room  # noqa: E402  (Builder, geometry, PNG writer)

ROOT = os.path.normpath(os.path.join(HERE, ".."))
SCENES = os.path.join(ROOT, "assets", "scenes")
OUT_DIR = os.path.join(ROOT, "assets", "truck_room")
PROBE = (0.0, 1.0, 0.0)


def read_gltf(path):
    """(json, [buffer bytes], base folder) of a .gltf with external buffers or a .glb."""
    base = os.path.dirname(path)
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        json_len = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + json_len])
        off = 20 + json_len
        bin_len = struct.unpack("<I", data[off:off + 4])[0]
        return doc, [data[off + 8:off + 8 + bin_len]], base
    doc = json.loads(data)
    bufs = [open(os.path.join(base, b["uri"]), "rb").read() for b in doc["buffers"]]
    return doc, bufs, base


class Scene(room.Builder):
    """The default room's Builder plus textures, images and samplers, and foreign glTF merging."""

    def __init__(self):
        super().__init__()
        self.textures, self.images, self.samplers = [], [], []

    def raw_view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target is not None:
            v["target"] = target
        self.views.append(v)
        self.bin.extend(data)
        return len(self.views) - 1

    def merge(self, path, prefix):
        """Appends every mesh, material and texture of the glTF at `path`; returns the new
        indices of its scene's root nodes (cameras and animations are left out)."""
        doc, bufs, base = read_gltf(path)
        view_map = []
        for v in doc.get("bufferViews", []):
            data = bufs[v.get("buffer", 0)][v.get("byteOffset", 0):
                                            v.get("byteOffset", 0) + v["byteLength"]]
            i = self.raw_view(data, v.get("target"))
            if "byteStride" in v:
                self.views[i]["byteStride"] = v["byteStride"]
            view_map.append(i)
        acc_base = len(self.accessors)
        for a in doc.get("accessors", []):
            a = dict(a)
            a["bufferView"] = view_map[a["bufferView"]]
            self.accessors.append(a)
        img_base = len(self.images)
        for im in doc.get("images", []):
            if "uri" in im:
                raw = open(os.path.join(base, im["uri"]), "rb").read()
                self.images.append({"bufferView": self.raw_view(raw), "mimeType": "image/png",
                                    "name": prefix + os.path.basename(im["uri"])})
            else:
                self.images.append({"bufferView": view_map[im["bufferView"]],
                                    "mimeType": im["mimeType"]})
        smp_base = len(self.samplers)
        self.samplers.extend(doc.get("samplers", []))
        tex_base = len(self.textures)
        for t in doc.get("textures", []):
            self.textures.append({"sampler": t["sampler"] + smp_base,
                                  "source": t["source"] + img_base})
        mat_base = len(self.materials)
        for m in doc.get("materials", []):
            m = json.loads(json.dumps(m))
            m["name"] = prefix + m.get("name", "material")
            pbr = m.get("pbrMetallicRoughness", {})
            if "baseColorTexture" in pbr:
                pbr["baseColorTexture"]["index"] += tex_base
            self.materials.append(m)
        mesh_base = len(self.meshes)
        for mesh in doc.get("meshes", []):
            prims = []
            for p in mesh["primitives"]:
                q = {"attributes": {k: v + acc_base for k, v in p["attributes"].items()},
                     "mode": p.get("mode", 4)}
                if "indices" in p:
                    q["indices"] = p["indices"] + acc_base
                if "material" in p:
                    q["material"] = p["material"] + mat_base
                prims.append(q)
            self.meshes.append({"name": prefix + mesh.get("name", "mesh"), "primitives": prims})
        # Nodes: cameras dropped; indices shifted.
        node_base = len(self.nodes)
        for i, n in enumerate(doc["nodes"]):
            q = {"name": prefix + n.get("name", "node%d" % i)}
            for key in ("matrix", "translation", "rotation", "scale"):
                if key in n:
                    q[key] = n[key]
            if "mesh" in n:
                q["mesh"] = n["mesh"] + mesh_base
            kids = [c + node_base for c in n.get("children", []) if "camera" not in doc["nodes"][c]]
            if kids:
                q["children"] = kids
            self.nodes.append(q)
        scene = doc["scenes"][doc.get("scene", 0)]
        return [r + node_base for r in scene["nodes"] if "camera" not in doc["nodes"][r]]

    def instance(self, roots, prefix):
        """Copies the node trees under `roots` (sharing their meshes); returns the new roots."""
        def copy(i):
            n = dict(self.nodes[i])
            n["name"] = prefix + n["name"].split("_", 1)[-1]
            if "children" in n:
                n["children"] = [copy(c) for c in n["children"]]
            self.nodes.append(n)
            return len(self.nodes) - 1
        return [copy(r) for r in roots]


def build():
    b = Scene()
    b.samplers.append({"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497})
    b.images.append({"uri": "floor.png", "name": "floor.png"})
    b.textures.append({"sampler": 0, "source": 0})
    quad = b.geometry(room.unit_quad())
    box = b.geometry(room.unit_box())
    roots = []

    floor = b.material("floor", (0.9, 0.9, 0.9), 0)
    roots.append(b.node("floor", mesh=b.mesh("floor", quad, floor),
                        rotation=room.quat_axis((1, 0, 0), -90), scale=(9, 9, 1)))
    walls = [("wall_north", (0, 2, -4.5), 0, (0.75, 0.78, 0.66)),
             ("wall_south", (0, 2, 4.5), 180, (0.66, 0.60, 0.80)),
             ("wall_east", (4.5, 2, 0), -90, (0.82, 0.66, 0.52)),
             ("wall_west", (-4.5, 2, 0), 90, (0.52, 0.74, 0.80))]
    for name, t, yaw, color in walls:
        mat = b.material(name, color)
        roots.append(b.node(name, mesh=b.mesh(name, quad, mat), translation=t,
                            rotation=room.quat_axis((0, 1, 0), yaw), scale=(9, 4, 1)))

    colours = [(0.85, 0.10, 0.05), (0.95, 0.55, 0.05), (0.90, 0.85, 0.10),
               (0.10, 0.65, 0.20), (0.10, 0.35, 0.85), (0.55, 0.15, 0.75)]
    for i, color in enumerate(colours):
        a = math.radians(60 * i)
        name = "column_%d" % i
        mat = b.material(name, color)
        roots.append(b.node(name, mesh=b.mesh(name, box, mat),
                            translation=(3.0 * math.cos(a), 1.4, -3.0 * math.sin(a)),
                            scale=(0.35, 2.8, 0.35)))

    # Ducks: the glb's root scales by 0.01 (about 1.54 m tall); 0.6 more makes 0.92 m.
    ducks = [((2.7, 0.0, 1.2), -120), ((-2.4, 0.0, -1.8), 40), ((0.8, 0.0, -3.2), 160)]
    duck = b.merge(os.path.join(SCENES, "duck", "Duck.glb"), "duck0_")
    for i, (t, yaw) in enumerate(ducks):
        kids = duck if i == 0 else b.instance(duck, "duck%d_" % i)
        roots.append(b.node("duck_%d" % i, translation=t, rotation=room.quat_axis((0, 1, 0), yaw),
                            scale=(0.6, 0.6, 0.6), children=kids))

    # The truck spans x -2.43..2.44, y 0..2.58, z -1.40..1.40 in its own frame: scale 0.3 and
    # lift so its middle sits on the probe.
    s = 0.3
    kids = b.merge(os.path.join(SCENES, "milk-truck", "CesiumMilkTruck.gltf"), "truck_")
    roots.append(b.node("milk_truck", translation=(PROBE[0], PROBE[1] - 1.29 * s, PROBE[2]),
                        rotation=room.quat_axis((0, 1, 0), 30), scale=(s, s, s), children=kids,
                        extras={"specula_reflector": True}))

    roots.append(b.node("probe", translation=PROBE, extras={"specula_probe": {"cell_size": 1.8}}))

    eye = (0.0, 1.7, 3.6)
    to = [PROBE[i] - eye[i] for i in range(3)]
    pitch = math.degrees(math.atan2(to[1], math.hypot(to[0], to[2])))
    roots.append(b.node("camera", camera=0, translation=eye,
                        rotation=room.quat_axis((1, 0, 0), pitch)))

    gltf = {
        "asset": {"version": "2.0", "generator": "specula scripts/make_truck_room.py",
                  "copyright": "milk truck: Cesium, CC-BY 4.0; duck: Sony, SCEA Shared Source "
                               "Licence (Khronos glTF sample models)"},
        "scene": 0,
        "scenes": [{"name": "truck_room", "nodes": roots}],
        "nodes": b.nodes,
        "meshes": b.meshes,
        "materials": b.materials,
        "textures": b.textures,
        "images": b.images,
        "samplers": b.samplers,
        "cameras": [{"type": "perspective", "name": "camera",
                     "perspective": {"yfov": 0.9, "aspectRatio": 4 / 3, "znear": 0.05,
                                     "zfar": 100.0}}],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"uri": "truck_room.bin", "byteLength": len(b.bin)}],
    }
    return gltf, bytes(b.bin)


def main():
    os.makedirs(OUT_DIR, exist_ok=True)
    gltf, binary = build()
    room.write_png(os.path.join(OUT_DIR, "floor.png"), 64, 64,
                   lambda x, y: (190, 185, 170) if ((x // 16) + (y // 16)) % 2 == 0
                   else (70, 75, 85))
    with open(os.path.join(OUT_DIR, "truck_room.bin"), "wb") as f:
        f.write(binary)
    with open(os.path.join(OUT_DIR, "truck_room.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    total = sum(os.path.getsize(os.path.join(OUT_DIR, n)) for n in os.listdir(OUT_DIR))
    print("wrote %s (%d bytes in all)" % (OUT_DIR, total), file=sys.stderr)


if __name__ == "__main__":
    main()
