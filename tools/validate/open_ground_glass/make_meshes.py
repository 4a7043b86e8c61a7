#!/usr/bin/env python3
"""The glass objects of this validation scene (issue 49; docs/validation.md "Glass on open ground"),
as single-file glTFs (their buffers as data URIs):

- glass_top.gltf: a 1.0 × 0.04 × 0.6 m slab of tinted glass (smooth, ior 1.5), its colour a
  KHR_materials_volume absorption (attenuationColor (0.55, 0.85, 0.8) at 0.15 m);
- glass_ball.gltf: a clear glass ball of radius 0.25 m (the materials harness's sphere, halved).

    python3 tools/validate/open_ground_glass/make_meshes.py"""
import base64
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "materials"))
import make  # noqa: E402  (the UV sphere)

TRANSMISSION = "KHR_materials_transmission"


def write_gltf(name, pos, nor, idx, material, out_dir=HERE):
    n = len(pos) // 3
    blob = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(nor), *nor)
    blob += struct.pack("<%dI" % len(idx), *idx)
    lo, hi = [min(pos[i::3]) for i in range(3)], [max(pos[i::3]) for i in range(3)]
    doc = {"asset": {"version": "2.0", "generator": "insitu tools/validate/open_ground_glass"},
           "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": name}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
           "materials": [material],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
                         {"bufferView": 0, "byteOffset": 12 * n, "componentType": 5126, "count": n, "type": "VEC3"},
                         {"bufferView": 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"}],
           "bufferViews": [{"buffer": 0, "byteLength": 24 * n},
                           {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(idx)}],
           "buffers": [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(doc, f)


def box(hx, hy, hz):
    """A box of half sizes (hx, hy, hz) about the origin: flat normals, wound outward (glTF's front)."""
    pos, nor, idx = [], [], []
    for axis in range(3):
        for sign in (1, -1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0, 0, 0]
                p[axis], p[u], p[v] = sign, a, b
                pos += [p[0] * hx, p[1] * hy, p[2] * hz]
                normal = [0, 0, 0]
                normal[axis] = sign
                nor += normal
            idx += [base + q for q in ([0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2])]
    return pos, nor, idx


def main():
    clear = {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0}
    write_gltf("glass_top", *box(0.5, 0.02, 0.3), {
        "name": "glass top", "pbrMetallicRoughness": clear,
        "extensions": {TRANSMISSION: {"transmissionFactor": 1},
                       "KHR_materials_volume": {"thicknessFactor": 0.04, "attenuationDistance": 0.15,
                                                "attenuationColor": [0.55, 0.85, 0.8]}}})
    pos, nor, _, idx = make.sphere(24, 48)
    write_gltf("glass_ball", [0.5 * p for p in pos], nor, idx,
               {"name": "clear glass", "pbrMetallicRoughness": clear, "extensions": {TRANSMISSION: {"transmissionFactor": 1}}})


if __name__ == "__main__":
    main()
