# A validation scene's error on blocks of pixels, where one pixel is all noise (glass, whose light
# comes by refracted paths alone): insitu's two renders (two seeds) against Cycles's two (truth.exr,
# truth2.exr), in Blender's Python (it reads EXR without other packages):
#
#   blender -b --factory-startup --python tools/validate/blocks.py -- DIR I1.exr I2.exr [BLOCK [BOX]]
#
# DIR is a tools/validate/run.sh output (its metrics.py masks, mask_objects.png and
# mask_changed.png). Each image is averaged over BLOCK × BLOCK pixels (default 8); a block belongs to
# a region where more than half its pixels do. Per region, as tools/validate/materials/compare.py
# per pixel: the relative RMSE of the mean of insitu's two against the mean of Cycles's two, each
# renderer's noise (half the RMSE between its two, relative), the excess
# sqrt(max(0, RMSE² − noise_insitu² − noise_cycles²)) and the brightness Σ Y_insitu / Σ Y_cycles.
# BOX, x0,y0,x1,y1 in pixels (from the top left, x1 and y1 excluded), splits the changed region
# into the blocks that lie in it ("changed_in_box") and the rest ("changed_out_of_box").
# Prints one line: BLOCKS {json}.
import json
import math
import os
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
d = os.path.abspath(argv[0])
block = int(argv[3]) if len(argv) > 3 else 8
box = [int(v) for v in argv[4].split(",")] if len(argv) > 4 else None


def load(name):
    img = bpy.data.images.load(os.path.join(d, name))
    px = [0.0] * (img.size[0] * img.size[1] * 4)
    img.pixels.foreach_get(px)
    return img.size[0], img.size[1], px


def blocks(w, h, px, channels):
    """Block means of the first `channels` channels: {(bx, by): [means]}."""
    out = {}
    for by in range(h // block):
        for bx in range(w // block):
            s = [0.0] * channels
            for y in range(by * block, (by + 1) * block):
                for x in range(bx * block, (bx + 1) * block):
                    i = 4 * (y * w + x)
                    for c in range(channels):
                        s[c] += px[i + c]
            out[(bx, by)] = [v / (block * block) for v in s]
    return out


def main():
    w, h, _ = load("truth.exr")
    i1, i2, c1, c2 = (blocks(w, h, load(n)[2], 3) for n in (argv[1], argv[2], "truth.exr", "truth2.exr"))
    result = {"block": block}
    lum = (0.2126, 0.7152, 0.0722)
    def in_box(k):  # blocks count from the bottom left, as Blender's pixels
        x, y = k[0] * block, h - (k[1] + 1) * block
        return box[0] <= x < box[2] and box[1] <= y < box[3]

    regions = [("objects", "objects", None), ("changed", "changed", None)]
    if box:
        regions += [("changed_in_box", "changed", True), ("changed_out_of_box", "changed", False)]
    for region, mask_name, inside in regions:
        mask = blocks(w, h, load("mask_" + mask_name + ".png")[2], 1)
        keys = [k for k, v in mask.items() if v[0] > 0.5 and (inside is None or in_box(k) == inside)]
        err = ref = ni = nc = ya = yt = 0.0
        for k in keys:
            for c in range(3):
                a, t = 0.5 * (i1[k][c] + i2[k][c]), 0.5 * (c1[k][c] + c2[k][c])
                err += (a - t) ** 2
                ref += t * t
                ni += (0.5 * (i1[k][c] - i2[k][c])) ** 2
                nc += (0.5 * (c1[k][c] - c2[k][c])) ** 2
                ya += lum[c] * a
                yt += lum[c] * t
        if not keys or ref <= 0:
            continue
        rmse, ni, nc = math.sqrt(err / ref), math.sqrt(ni / ref), math.sqrt(nc / ref)
        result[region] = {"blocks": len(keys), "relative_rmse": rmse, "insitu_noise": ni, "cycles_noise": nc,
                          "excess": math.sqrt(max(0.0, rmse * rmse - ni * ni - nc * nc)), "brightness": ya / yt}
    print("BLOCKS " + json.dumps(result), flush=True)


main()
