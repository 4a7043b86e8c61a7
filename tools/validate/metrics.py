# The error of insitu against the Cycles truth of a validation scene (issue 12), in Blender's
# Python (it reads EXR without other packages):
#
#   blender -b --factory-startup --python tools/validate/metrics.py -- DIR [IMAGE.exr]
#
# DIR holds truth.exr, truth2.exr (another seed), photo.exr, coverage.exr (cycles_render.py) and
# insitu's linear composite (default insitu.exr). Regions:
#   objects  the objects' coverage α > 0.01 (coverage.exr);
#   changed  the other pixels where the objects change the truth: |Y_truth − Y_photo|, averaged over
#            3 × 3 pixels, above 3 % of Y_photo (shadows, bounce light);
#   all      their union.
# Relative RMSE over a region R, as insitu compare: sqrt(mean_R (a − t)²) / sqrt(mean_R t²) over
# the RGB channels. "noise" is the truth's own: the same figure between truth and truth2, divided
# by √2 (the error of one render against the true image). "brightness" is Σ_R Y_a / Σ_R Y_t.
# Prints one JSON object and writes DIR/metrics.json and the masks as PNG.
import json
import math
import os
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
d = os.path.abspath(argv[0])
image_name = argv[1] if len(argv) > 1 else "insitu.exr"


def load(name):
    """The image's RGBA, its negative and non-finite values taken as 0, as insitu reads its photo:
    an HDRI's negative texels (a processing artefact) reach Cycles's camera as they are, and would
    otherwise count as pixels the objects changed (their luminance below the 3 % test's floor)."""
    img = bpy.data.images.load(os.path.join(d, name))
    w, h = img.size
    px = [0.0] * (w * h * 4)
    img.pixels.foreach_get(px)
    return w, h, [v if v > 0 and math.isfinite(v) else 0.0 for v in px]


def lum(px, i):
    return 0.2126 * px[4 * i] + 0.7152 * px[4 * i + 1] + 0.0722 * px[4 * i + 2]


def main():
    w, h, truth = load("truth.exr")
    _, _, photo = load("photo.exr")
    _, _, cover = load("coverage.exr")
    _, _, ours = load(image_name)
    truth2 = load("truth2.exr")[2] if os.path.exists(os.path.join(d, "truth2.exr")) else None
    n = w * h
    objects = [cover[4 * i + 3] > 0.01 for i in range(n)]
    diff = [abs(lum(truth, i) - lum(photo, i)) for i in range(n)]
    changed = []
    for y in range(h):
        for x in range(w):
            s, k = 0.0, 0
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    xx, yy = x + dx, y + dy
                    if 0 <= xx < w and 0 <= yy < h:
                        s += diff[yy * w + xx]
                        k += 1
            i = y * w + x
            changed.append(not objects[i] and s / k > 0.03 * max(lum(photo, i), 1e-6))
    regions = {"objects": objects, "changed": changed, "all": [a or b for a, b in zip(objects, changed)]}

    def rel_rmse(a, t, mask):
        se = st = 0.0
        m = 0
        for i in range(n):
            if mask[i]:
                for c in range(3):
                    se += (a[4 * i + c] - t[4 * i + c]) ** 2
                    st += t[4 * i + c] ** 2
                m += 1
        return math.sqrt(se / st) if st > 0 else 0.0, m

    out = {"image": image_name, "width": w, "height": h}
    for name, mask in regions.items():
        err, m = rel_rmse(ours, truth, mask)
        ya = sum(lum(ours, i) for i in range(n) if mask[i])
        yt = sum(lum(truth, i) for i in range(n) if mask[i])
        r = {"pixels": m, "relative_rmse": err, "brightness": ya / yt if yt > 0 else 1.0}
        if truth2:
            r["truth_noise"] = rel_rmse(truth2, truth, mask)[0] / math.sqrt(2)
        out[name] = r
    for name, mask in regions.items():
        img = bpy.data.images.new(name, w, h)
        img.pixels.foreach_set([v for i in range(n) for v in ((1.0,) * 3 if mask[i] else (0.0,) * 3) + (1.0,)])
        img.filepath_raw = os.path.join(d, "mask_" + name + ".png")
        img.file_format = "PNG"
        img.save()
    with open(os.path.join(d, "metrics.json"), "w") as f:
        json.dump(out, f, indent=2)
    print("METRICS " + json.dumps(out), flush=True)


main()
