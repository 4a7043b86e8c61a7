#!/usr/bin/python3
# Speckle far from the objects (docs/performance.md, "Speckle far from the objects"): over the
# pixels farther than 0.5 m from every object, the share whose composite departs from a converged
# reference by more than 2 % (issue 50's preview goal), and, given a second render with another
# seed, the seed-to-seed noise alone.
#   build/insitu calibrate --points scenes/demo/points.json --image scenes/demo/photo.jpg -o CAM.json
#   /usr/bin/python3 bench/far_speckle.py scenes/demo/scene.json CAM.json A.layers.exr REF.layers.exr [B.layers.exr]
# With FAR_SPECKLE_MAP=OUT.png it also says how many of the pixels off were left as the photo
# (the same sums with and without the objects in every sample) and draws them: red over A's
# composite, the far pixels tinted green.
# A pixel's world point comes from the reference's depth layer (camera-space z) and the camera's
# pose (x_cam = R x_world + t); a pixel any of whose reference samples met an object (coverage > 0)
# is not far, whatever its mean depth. Its distance to the objects is to points about 5 cm apart on their
# triangles (OBJ meshes, `translate` and `rotate` about +y; no `scale`). Needs numpy and
# OpenImageIO's Python module (python3-openimageio).
import json
import os
import sys

import numpy as np
import OpenImageIO as oiio

LUMA = np.array([0.2126, 0.7152, 0.0722])


def channels(path, names):
    buf = oiio.ImageBuf(path)
    have = list(buf.spec().channelnames)
    return buf.get_pixels(oiio.FLOAT)[:, :, [have.index(n) for n in names]]


def object_points(path, rotate_deg, translate):
    vertices, triangles = [], []
    for line in open(path):
        s = line.split()
        if s and s[0] == 'v':
            vertices.append([float(x) for x in s[1:4]])
        elif s and s[0] == 'f':
            idx = [int(t.split('/')[0]) - 1 for t in s[1:]]
            triangles += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    a = np.radians(rotate_deg)
    rot = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    v = np.array(vertices) @ rot.T + np.array(translate)
    rng = np.random.default_rng(0)
    points = [v]
    for tri in triangles:
        p0, p1, p2 = v[tri]
        count = int(0.5 * np.linalg.norm(np.cross(p1 - p0, p2 - p0)) / 0.0025) + 1
        u = rng.random((count, 2))
        u[u.sum(1) > 1] = 1 - u[u.sum(1) > 1]
        points.append(p0 + u[:, :1] * (p1 - p0) + u[:, 1:] * (p2 - p0))
    return np.concatenate(points)


def distance_to_objects(scene_path, camera, depth):
    folder = os.path.dirname(scene_path)
    scene = json.load(open(scene_path))
    points = np.concatenate([object_points(os.path.join(folder, o['mesh']), o.get('rotate', 0),
                                           o.get('translate', [0, 0, 0])) for o in scene['objects']])
    k, pose = camera['intrinsics'], camera['pose']
    h, w = depth.shape
    u, v = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    x_cam = np.stack([(u - k['cx']) / k['fx'] * depth, (v - k['cy']) / k['fy'] * depth, depth], -1)
    x_world = (x_cam.reshape(-1, 3) - np.array(pose['t'])) @ np.array(pose['R'])
    dist = np.full(len(x_world), np.inf)
    for i in range(0, len(points), 4000):
        q = points[i:i + 4000]
        for j in range(0, len(x_world), 20000):
            d = np.sqrt(((x_world[j:j + 20000, None, :] - q[None]) ** 2).sum(-1)).min(1)
            dist[j:j + 20000] = np.minimum(dist[j:j + 20000], d)
    return dist.reshape(h, w)


def draw_map(out_path, test_path, off, far):
    same = np.all(channels(test_path, ['with.R', 'with.G', 'with.B']) ==
                  channels(test_path, ['without.R', 'without.G', 'without.B']), -1)
    print(f"off by more than 2 %: {off.sum()} pixels, {(off & same).sum()} of them left as the photo")
    rgb = np.clip(channels(test_path, 'RGB'), 0, 1) ** (1 / 2.2)
    rgb = np.where(far[..., None], 0.6 * rgb + [0, 0.12, 0], 0.5 * rgb)
    grown = off.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            grown |= np.roll(np.roll(off, dy, 0), dx, 1)
    rgb[grown] = [1, 0, 0]
    out = oiio.ImageBuf(np.ascontiguousarray(rgb, dtype=np.float32))
    if not out.write(out_path, oiio.UINT8):
        sys.exit(f"{out_path}: {out.geterror()}")


def main():
    scene_path, camera_path, test_path, ref_path = sys.argv[1:5]
    depth = channels(ref_path, ['depth.Z'])[:, :, 0]
    # A pixel that shows an object is not far from it, whatever its depth: at an object's edge the
    # depth is the mean of the object's and of the surface behind it, a point near neither.
    covered = channels(ref_path, ['objects.A'])[:, :, 0] > 0
    far = (distance_to_objects(scene_path, json.load(open(camera_path)), depth) > 0.5) & (depth > 0) & ~covered
    ref = channels(ref_path, 'RGB') @ LUMA
    test = channels(test_path, 'RGB') @ LUMA
    rel = np.abs(test - ref)[far] / np.maximum(ref[far], 1e-6)
    print(f"far pixels: {far.sum()} of {far.size}; off by more than 2 %: {100 * (rel > 0.02).mean():.2f} %, "
          f"more than 5 %: {100 * (rel > 0.05).mean():.2f} %, at most {100 * rel.max():.1f} %")
    if os.environ.get('FAR_SPECKLE_MAP'):
        draw_map(os.environ['FAR_SPECKLE_MAP'], test_path, far & (np.abs(test - ref) > 0.02 * np.maximum(ref, 1e-6)), far)
    if len(sys.argv) > 5:
        other = channels(sys.argv[5], 'RGB') @ LUMA
        noise = np.abs(test - other)[far] / np.maximum(ref[far], 1e-6) / np.sqrt(2)
        print(f"seed-to-seed noise over them: rms {100 * np.sqrt((noise ** 2).mean()):.2f} %, "
              f"above 2 %: {100 * (noise > 0.02).mean():.2f} %")


if __name__ == '__main__':
    main()
