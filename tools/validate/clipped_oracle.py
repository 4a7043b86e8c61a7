"""Where the error of recovered clipped light lies (issue 13): oracles from the HDR shots' cube.

    bash tools/validate/jpeg_shots.sh OUT 256              # OUT/scene_jpeg.json and its shots
    /usr/bin/python3 tools/validate/clipped_oracle.py OUT  # needs numpy, scipy, OpenImageIO

Runs `insitu cubemap` on the HDR shots (OUT/scene.json), on the JPEG shots with inverse lighting
(OUT/scene_jpeg.json) and without it, and compares the three cubes:

- the irradiance's 9 spherical-harmonic coefficients of each (luminance), E_lm = A_l L_lm with
  A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (Ramamoorthi & Hanrahan 2001, "An efficient
  representation for irradiance environment maps"): all that a matt convex object's shading can
  tell of the light, and so all a grey ball can;
- per clipped region (texels whose largest channel is at least 97 % of the JPEG's white, the
  exposure; 4-connected on each face), the power each cube adds to the clipped value,
  sum (Y - Y_jpeg) dOmega.

It writes two cubes to render in place of the recovered one, each with OUT/scene_oracle_*.json:

- texels: the JPEG cube with the HDR cube's values in the clipped texels (the light recovered
  perfectly: what is left is the JPEG itself);
- power: the JPEG cube with each clipped region given the HDR cube's added power, spread evenly
  over it in the added light's own colour (the right energy and colour per region: what placement
  within a region costs);
- power_white: the same in the clipped value's colour (white where all channels clipped): what
  the colour costs. Until 2026-11-25 this was the "power" oracle, and its error was read as the
  cost of placement (docs/validation.md);
- parts: the same (own colour) for each part as inverse lighting cuts them (a region's texels in one block of
  b x b of a face, b = max(2, n / 16, ceil(sqrt(clipped texels / 48))), inverse_lighting.cpp):
  the best the fit's unknowns can do.

Then, for each:  build/insitu render OUT/scene_oracle_texels.json --spp 256 -o OUT/o_texels.exr
--layers none, and tools/validate/metrics.py as for any render.
"""
import json
import os
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio
import scipy.ndimage as nd

LUMA = np.array([0.2126, 0.7152, 0.0722])
FACES = ["+x", "-x", "+y", "-y", "+z", "-z"]


def read(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[:, :, :3].astype(np.float64)


def write(path, pixels):
    n = pixels.shape[1]
    buf = oiio.ImageBuf(oiio.ImageSpec(n, 6 * n, 3, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(), pixels.astype(np.float32))
    if not buf.write(path):
        sys.exit(f"clipped_oracle.py: {path}: {buf.geterror()}")


def directions_and_solid_angles(n):
    """Texel centres' unit directions and solid angles, faces stacked as insitu's cube strip
    (src/light/cubemap.cpp face_to_direction; the solid angle dA / r^3 at the centre)."""
    c = (np.arange(n) + 0.5) / n * 2 - 1
    s, t = np.meshgrid(c, c)
    one = np.ones_like(s)
    faces = [(one, -t, -s), (-one, -t, s), (s, one, t), (s, -one, -t), (s, -t, one), (-s, -t, -one)]
    d = np.concatenate([np.stack(f, -1) for f in faces], 0)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    omega = np.tile((1 + s * s + t * t) ** -1.5 * (2 / n) ** 2, (6, 1))
    return d, omega


def sh9_irradiance(y, d, omega):
    x_, y_, z_ = d[..., 0], d[..., 1], d[..., 2]
    basis = [np.ones_like(x_), y_, z_, x_, x_ * y_, y_ * z_, 3 * z_ * z_ - 1, x_ * z_, x_ * x_ - y_ * y_]
    a = [np.pi] + [2 * np.pi / 3] * 3 + [np.pi / 4] * 5
    return np.array([al * (b * y * omega).sum() for al, b in zip(a, basis)])


def cubemap(insitu, scene, folder):
    os.makedirs(folder, exist_ok=True)
    run = subprocess.run([insitu, "cubemap", scene, "-o", folder], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"clipped_oracle.py: insitu cubemap {scene}: {run.stderr.strip()}")
    return read(os.path.join(folder, "cube.exr"))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = os.path.abspath(sys.argv[1])
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    insitu = os.environ.get("INSITU", os.path.join(root, "build", "insitu"))
    jpeg = json.load(open(os.path.join(out, "scene_jpeg.json")))
    exposure = float(jpeg["environment"]["exposure"])
    off = json.loads(json.dumps(jpeg))
    off["environment"]["inverse_lighting"] = False
    json.dump(off, open(os.path.join(out, "scene_jpeg_off.json"), "w"), indent=1)
    hdr = cubemap(insitu, os.path.join(out, "scene.json"), os.path.join(out, "oracle", "hdr"))
    fit = cubemap(insitu, os.path.join(out, "scene_jpeg.json"), os.path.join(out, "oracle", "fit"))
    raw = cubemap(insitu, os.path.join(out, "scene_jpeg_off.json"), os.path.join(out, "oracle", "jpeg"))
    n = raw.shape[1]
    d, omega = directions_and_solid_angles(n)
    y = {k: v @ LUMA for k, v in (("hdr", hdr), ("fit", fit), ("raw", raw))}

    np.set_printoptions(precision=3, suppress=True, linewidth=120)
    print("irradiance's SH coefficients (luminance), E_00 E_1-1 E_10 E_11 E_2-2 E_2-1 E_20 E_21 E_22:")
    for name, label in (("hdr", "HDR shots"), ("fit", "JPEG, recovered"), ("raw", "JPEG, lower bound")):
        print(f"  {label:18s}", sh9_irradiance(y[name], d, omega))

    clipped = raw.max(axis=2) >= 0.97 * exposure
    texels, power, parts, power_white = raw.copy(), raw.copy(), raw.copy(), raw.copy()
    block = max(2, n // 16, int(np.ceil(np.sqrt(clipped.sum() / 48))))
    ii, jj = np.meshgrid(np.arange(n), np.arange(n))
    cell = np.tile((jj // block) * n + ii // block, (6, 1))

    def scale_to_hdr(m, cube, white=False):
        # The HDR cube's added power over m, spread over m in proportion to the clipped value's
        # luminance, in the added light's own colour (luminance 1), or in the clipped value's
        # colour (white) with `white`.
        base = (y["raw"] * omega)[m].sum()
        added_rgb = ((hdr - raw) * omega[..., None])[m].sum(0)
        added = added_rgb @ LUMA
        if white or added <= 0:
            cube[m] = raw[m] * (1 + max(0.0, added) / base)
        else:
            cube[m] = raw[m] + (added / base) * y["raw"][m][:, None] * (added_rgb / added)[None, :]
    texels[clipped] = hdr[clipped]
    print("clipped regions (2 texels or more): texels, direction, added power HDR / recovered")
    rows = []
    for f in range(6):
        face = slice(f * n, (f + 1) * n)
        labels, count = nd.label(clipped[face])
        for k in range(1, count + 1):
            m = np.zeros_like(clipped)
            m[face] = labels == k
            added_hdr = ((y["hdr"] - y["raw"]) * omega)[m].sum()
            added_fit = ((y["fit"] - y["raw"]) * omega)[m].sum()
            scale_to_hdr(m, power)
            scale_to_hdr(m, power_white, white=True)
            for c in np.unique(cell[m]):
                scale_to_hdr(m & (cell == c), parts)
            direction = (d[m] * omega[m][:, None]).sum(0)
            rows.append((added_hdr, m.sum(), FACES[f], direction / np.linalg.norm(direction), added_fit))
    for added_hdr, count, face, direction, added_fit in sorted(rows, key=lambda r: -r[0]):
        if count >= 2:
            print(f"  {count:5d} on {face} toward {direction}: {added_hdr:8.4f} / {added_fit:8.4f}")
    for name, cube in (("texels", texels), ("power", power), ("parts", parts), ("power_white", power_white)):
        path = os.path.join(out, "oracle", f"cube_{name}.exr")
        write(path, cube)
        scene = json.loads(json.dumps(jpeg))
        scene["environment"] = {"image": path, "exposure": 1.0}
        scene.pop("references", None)
        json.dump(scene, open(os.path.join(out, f"scene_oracle_{name}.json"), "w"), indent=1)
        print(f"wrote {path} and {os.path.join(out, f'scene_oracle_{name}.json')}")


if __name__ == "__main__":
    main()
