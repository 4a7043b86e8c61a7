#!/usr/bin/env python3
"""The material validation scenes (issue 49; docs/validation.md "Materials"): a sphere in each
material class as a glTF 2.0 file, under one of ../shared/data's HDRIs given directly as the
environment (on a cube of 1024² faces), seen by a 30° camera over a black photo: the composite's object pixels are the
render alone, and only the material differs between insitu and Cycles.

    python3 tools/validate/materials/make.py OUT_DIR [HDRI]

writes OUT_DIR/<material>.gltf (+ .bin), OUT_DIR/black.png and OUT_DIR/<material>.json (an insitu
scene). tools/validate/materials/run.sh renders them with both and compares."""
import json
import math
import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))

# name: (base colour (RGBA), metallic, roughness, texture, more of the glTF material). Classes insitu
# renders today; glass follows with its lobes. MATERIALS_ONLY=a,b makes only those.
COAT = "KHR_materials_clearcoat"
MATERIALS = {
    "rough_dielectric": ((0.8, 0.3, 0.2, 1), 0.0, 0.6, None, {}),
    "polished_dielectric": ((0.1, 0.25, 0.6, 1), 0.0, 0.15, None, {}),
    "white_dielectric": ((0.9, 0.9, 0.9, 1), 0.0, 0.4, None, {}),
    "gold": ((1.0, 0.77, 0.34, 1), 1.0, 0.3, None, {}),
    "polished_steel": ((0.56, 0.57, 0.58, 1), 1.0, 0.1, None, {}),
    "half_metal_textured": ((1.0, 1.0, 1.0, 1), 0.5, 0.45, "checker", {}),
    # A lacquer: a glossy coat over a textured, rough wood-brown base.
    "lacquered_wood": ((1.0, 1.0, 1.0, 1), 0.0, 0.6, "checker",
                       {"extensions": {COAT: {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}}),
    "satin_coat": ((0.6, 0.1, 0.1, 1), 0.0, 0.35, None,
                   {"extensions": {COAT: {"clearcoatFactor": 0.6, "clearcoatRoughnessFactor": 0.3}}}),
    "coated_gold": ((1.0, 0.77, 0.34, 1), 1.0, 0.5, None,
                    {"extensions": {COAT: {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.1}}}),
    # An upholstery fabric: a rough, dark base under a pale sheen.
    "sheen_fabric": ((0.25, 0.05, 0.08, 1), 0.0, 0.8, None,
                     {"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.6, 0.5, 0.55],
                                                             "sheenRoughnessFactor": 0.35}}}),
    "emissive": ((0.2, 0.2, 0.2, 1), 0.0, 0.5, None,
                 {"emissiveFactor": [1.0, 0.6, 0.3],
                  "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}}),
    "alpha_mask": ((1.0, 1.0, 1.0, 1), 0.0, 0.5, "checker_alpha", {"alphaMode": "MASK", "alphaCutoff": 0.5}),
    "alpha_blend": ((0.8, 0.8, 0.8, 0.4), 0.0, 0.4, None, {"alphaMode": "BLEND"}),
}


def sphere(rings=48, segments=96):
    """A UV sphere of radius 0.5: positions, normals, glTF UVs (v down), uint32 indices."""
    pos, nor, uv, idx = [], [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            pos += [0.5 * c for c in n]
            nor += list(n)
            uv += [j / segments, i / rings]
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            if i > 0:
                idx += [a, b, a + 1]
            if i < rings - 1:
                idx += [a + 1, b, b + 1]
    return pos, nor, uv, idx


def checker_png(path, alpha=False):
    """A 256² checker of 32-texel squares; with alpha, the dark squares have alpha 0."""
    colours = "color1=0.9,0.85,0.8,1:color2=0.2,0.12,0.08,0" if alpha else "color1=0.9,0.85,0.8:color2=0.2,0.12,0.08"
    subprocess.check_call(["oiiotool", "--pattern", "checker:width=32:height=32:" + colours,
                           "256x256", "4" if alpha else "3", "-d", "uint8", "-o", path])


def write_gltf(out, name, base, metallic, roughness, texture, more):
    pos, nor, uv, idx = sphere()
    n = len(pos) // 3
    blob = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(nor), *nor)
    blob += struct.pack("<%df" % len(uv), *uv) + struct.pack("<%dI" % len(idx), *idx)
    o_nor, o_uv, o_idx = 12 * n, 24 * n, 32 * n
    pbr = {"baseColorFactor": list(base), "metallicFactor": metallic, "roughnessFactor": roughness}
    doc = {
        "asset": {"version": "2.0", "generator": "insitu tools/validate/materials/make.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": name}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [dict({"name": name, "pbrMetallicRoughness": pbr}, **more)],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
            {"bufferView": 0, "byteOffset": o_nor, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 0, "byteOffset": o_uv, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": o_idx}, {"buffer": 0, "byteOffset": o_idx, "byteLength": 4 * len(idx)}],
        "buffers": [{"uri": name + ".bin", "byteLength": len(blob)}],
    }
    if texture:
        checker_png(os.path.join(out, texture + ".png"), alpha=texture.endswith("alpha"))
        doc["images"] = [{"uri": texture + ".png"}]
        doc["textures"] = [{"source": 0}]
        pbr["baseColorTexture"] = {"index": 0}
    with open(os.path.join(out, name + ".bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(out, name + ".gltf"), "w") as f:
        json.dump(doc, f)


def main():
    out = os.path.abspath(sys.argv[1])
    hdri = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "..", "shared", "data", "hdri",
                                                                              "interior.exr"))
    os.makedirs(out, exist_ok=True)
    subprocess.check_call(["oiiotool", "--pattern", "constant:color=0,0,0", "320x240", "3", "-d", "uint8", "-o",
                           os.path.join(out, "black.png")])
    only = [m for m in os.environ.get("MATERIALS_ONLY", "").split(",") if m]
    for name, (base, metallic, roughness, texture, more) in MATERIALS.items():
        if only and name not in only:
            continue
        write_gltf(out, name, base, metallic, roughness, texture, more)
        scene = {"photo": "black.png",
                 "camera": {"eye": [0.0, 0.45, 3.4], "look": [0.0, 0.0, 0.0], "hfov_deg": 30},
                 # 1024² faces (the HDRI's 1024 × 512 upsampled): finer than the polished lobes, so that
                 # insitu's nearest-texel cube and Cycles's bilinear world differ below the materials.
                 "environment": {"image": hdri, "face_size": 1024},
                 "objects": [{"mesh": name + ".gltf", "rotate": 30}],
                 "render": {"integrator": "path", "spp": 1024, "max_depth": 8},
                 "output": {"image": "insitu_" + name + ".exr", "layers": "none"}}
        with open(os.path.join(out, name + ".json"), "w") as f:
            json.dump(scene, f, indent=1)
    print("materials: wrote", len(only) if only else len(MATERIALS), "scenes to", out)


if __name__ == "__main__":
    main()
