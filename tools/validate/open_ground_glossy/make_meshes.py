#!/usr/bin/env python3
"""The glossy objects of this validation scene (issue 49's time-to-2 % goal on a glossy scene;
docs/performance.md "A glossy scene"), as single-file glTFs of the materials harness's sphere:

- polished.gltf: a red dielectric of roughness 0.15;
- steel.gltf: a metal of roughness 0.25;
- lacquer.gltf: brown wood of roughness 0.6 under a clear coat 1 of roughness 0.1.

    python3 tools/validate/open_ground_glossy/make_meshes.py"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
VALIDATE = os.path.dirname(HERE)
sys.path[:0] = [os.path.join(VALIDATE, "materials"), os.path.join(VALIDATE, "open_ground_glass")]
import make  # noqa: E402  (the UV sphere)
import make_meshes as glass  # noqa: E402  (the glTF writer)


def main():
    pos, nor, _, idx = make.sphere(24, 48)
    pbr = lambda base, metallic, roughness: {"baseColorFactor": base + [1], "metallicFactor": metallic,
                                             "roughnessFactor": roughness}
    materials = {
        "polished": {"name": "polished red", "pbrMetallicRoughness": pbr([0.6, 0.08, 0.05], 0, 0.15)},
        "steel": {"name": "steel", "pbrMetallicRoughness": pbr([0.75, 0.75, 0.77], 1, 0.25)},
        "lacquer": {"name": "lacquered wood", "pbrMetallicRoughness": pbr([0.35, 0.18, 0.08], 0, 0.6),
                    "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.1}}},
    }
    for name, material in materials.items():
        glass.write_gltf(name, pos, nor, idx, material, HERE)


if __name__ == "__main__":
    main()
