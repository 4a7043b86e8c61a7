# insitu's renders of a material scene against Cycles's (tools/validate/materials/run.sh), in
# Blender's Python (it reads EXR without other packages):
#
#   blender -b --factory-startup --python tools/validate/materials/compare.py -- I1.exr I2.exr C1.exr C2.exr
#
# Each renderer rendered the scene twice with different seeds; each image is the mean of its two.
# The object's pixels are those where any render differs from the black photo. Relative RMSE over
# them, as insitu compare: sqrt(mean (a − t)²) / sqrt(mean t²) over RGB. A renderer's noise is the
# same figure between its two halves, / 2 (the error of their mean); "excess" is what the
# difference holds beyond both noises, sqrt(max(0, RMSE² − noise_insitu² − noise_cycles²)): the
# material's bias, to within the noises' own uncertainty. "brightness" is Σ Y_insitu / Σ Y_cycles.
# Prints one line: METRICS {json}.
import json
import math
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:]


def load(path):
    img = bpy.data.images.load(path)
    px = [0.0] * (img.size[0] * img.size[1] * 4)
    img.pixels.foreach_get(px)
    return px


i1, i2, c1, c2 = (load(p) for p in argv[:4])
err = ref = noise_i = noise_c = ya = yt = 0.0
count = 0
w = (0.2126, 0.7152, 0.0722)
for i in range(0, len(i1), 4):
    if max(i1[i:i + 3] + i2[i:i + 3] + c1[i:i + 3] + c2[i:i + 3]) <= 0:
        continue
    count += 1
    for c in range(3):
        a, t = 0.5 * (i1[i + c] + i2[i + c]), 0.5 * (c1[i + c] + c2[i + c])
        err += (a - t) ** 2
        ref += t * t
        noise_i += (0.5 * (i1[i + c] - i2[i + c])) ** 2
        noise_c += (0.5 * (c1[i + c] - c2[i + c])) ** 2
        ya += w[c] * a
        yt += w[c] * t
rmse, ni, nc = math.sqrt(err / ref), math.sqrt(noise_i / ref), math.sqrt(noise_c / ref)
print("METRICS " + json.dumps({"pixels": count, "relative_rmse": rmse, "insitu_noise": ni, "cycles_noise": nc,
                               "excess": math.sqrt(max(0.0, rmse * rmse - ni * ni - nc * nc)),
                               "brightness": ya / yt}), flush=True)
