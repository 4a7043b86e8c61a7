#!/usr/bin/python3
# The demo room as a catalogue still: scenes/demo copied to OUT with its photo resized SCALE times
# (default 3: 1920 × 1440) and its clicked points scaled to match, for the benchmarks of a still
# (bench/still.sh, bench/farm/startup.sh --big).
#   /usr/bin/python3 bench/big_demo.py OUT [SCALE]
# Needs OpenImageIO's Python module (python3-openimageio). OUT must not exist.
import json
import os
import shutil
import sys

import OpenImageIO as oiio


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: big_demo.py OUT [SCALE]")
    out, scale = sys.argv[1], int(sys.argv[2]) if len(sys.argv) == 3 else 3
    if os.path.exists(out):
        sys.exit(f"big_demo: {out}: exists already")
    shutil.copytree(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scenes', 'demo'), out,
                    ignore=shutil.ignore_patterns('out'))
    src = oiio.ImageBuf(f"{out}/photo.jpg")
    spec = src.spec()
    dst = oiio.ImageBufAlgo.resize(src, roi=oiio.ROI(0, scale * spec.width, 0, scale * spec.height, 0, 1, 0, 3))
    for a in spec.extra_attribs:  # the EXIF exposure, which links the photo to the shots
        dst.specmod().attribute(a.name, a.type, a.value)
    dst.set_write_format(oiio.UINT8)
    if not dst.write(f"{out}/photo.jpg"):
        sys.exit(f"big_demo: {out}/photo.jpg: {dst.geterror()}")
    points = json.load(open(f"{out}/points.json"))
    for p in points:  # pixel coordinates from the top-left corner: × scale exactly
        p["uv"] = [scale * p["uv"][0], scale * p["uv"][1]]
    json.dump(points, open(f"{out}/points.json", "w"), indent=2)


if __name__ == '__main__':
    main()
