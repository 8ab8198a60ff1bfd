#!/usr/bin/env python3
"""A parallel camera grid made into a rectified gantry, named as the Stanford archive names its
files (docs/fidelity.md, "The shop rectified and named as a gantry").

The research community publishes most light fields rectified to a plane (shifted sensors: zero
disparity on that plane, both signs of disparity around it) with the positions in the names and
no focal length. No such folder of real photographs is here; this makes one from a folder of
parallel cameras whose names carry their positions in mm (the Blender grid's
`NAME_RR_CC_Y_X_F_W.jpg`, Y = -y, X = x: `shared/data/shop-center-9x9`). Each photograph is
shrunk by SCALE (area average) and cropped to a window that moves STEP whole pixels a grid step
against its camera's position, so that the plane where the views move by STEP px between
neighbours has zero disparity; nothing is resampled but the shrink. Written as
`OUT/NAME_RR_CC_Y_X_.png`, RR and CC counted from 00 at the grid's first row and column, Y and X
the source's numbers unchanged.

    bench/as_gantry.py DATA_DIR OUT_DIR [--step PX] [--scale S]

Then `bench/heldout.py OUT_DIR WORK` measures its held-out views.
"""
import argparse
import glob
import os
import re
import sys

import cv2


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("out")
    ap.add_argument("--step", type=int, default=3, help="px a grid step (default 3)")
    ap.add_argument("--scale", type=float, default=1.0, help="shrink first (default 1)")
    args = ap.parse_args()
    pattern = re.compile(r"^(.*?)_(\d+)_(\d+)_(-?[0-9.]+)_(-?[0-9.]+)_[0-9.]+_[0-9.]+\.(jpg|png)$")
    cams = []
    for path in sorted(glob.glob(os.path.join(args.data, "*"))):
        m = pattern.match(os.path.basename(path))
        if m:
            cams.append((path, int(m[2]), int(m[3]), m[4], m[5]))
    if len(cams) < 4:
        sys.exit(f"{args.data}: no files named NAME_RR_CC_Y_X_F_W.jpg (a Blender grid)")
    rows = sorted({c[1] for c in cams})
    cols = sorted({c[2] for c in cams})
    ys = sorted({float(c[3]) for c in cams})
    xs = sorted({float(c[4]) for c in cams})
    pitch_y = (ys[-1] - ys[0]) / max(1, len(ys) - 1)
    pitch_x = (xs[-1] - xs[0]) / max(1, len(xs) - 1)
    mid_y, mid_x = (ys[0] + ys[-1]) / 2, (xs[0] + xs[-1]) / 2
    reach_y = round((ys[-1] - mid_y) / pitch_y) * args.step
    reach_x = round((xs[-1] - mid_x) / pitch_x) * args.step
    os.makedirs(args.out, exist_ok=True)
    for path, r, c, y_name, x_name in cams:
        img = cv2.imread(path, cv2.IMREAD_COLOR)
        if img is None:
            sys.exit(f"{path}: not an image OpenCV reads")
        if args.scale != 1.0:
            img = cv2.resize(img, None, fx=args.scale, fy=args.scale, interpolation=cv2.INTER_AREA)
        h, w = img.shape[:2]
        # A point of the plane sits f x / Z0 left of the image centre in a camera at x (x along
        # the cameras' right), and f y / Z0 below it in one at y = -Y (image rows down).
        kx = round((float(x_name) - mid_x) / pitch_x)
        ky = round((float(y_name) - mid_y) / pitch_y)
        ox = reach_x - args.step * kx
        oy = reach_y - args.step * ky
        crop = img[oy:oy + h - 2 * reach_y, ox:ox + w - 2 * reach_x]
        name = f"{os.path.basename(path).split('_')[0].replace(' ', '')}_" \
               f"{rows.index(r):02d}_{cols.index(c):02d}_{y_name}_{x_name}_.png"
        cv2.imwrite(os.path.join(args.out, name), crop)
    print(f"wrote {len(cams)} views of {w - 2 * reach_x}x{h - 2 * reach_y} to {args.out} "
          f"({args.step} px a grid step at the zero-disparity plane)")


if __name__ == "__main__":
    main()
