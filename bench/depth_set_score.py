#!/usr/bin/env python3
"""Scores a depth set (`lfcam depth --all`) against the truth (`lfcam simulate lightfield
--depth-out`): per view the share of samples whose depth lies within 1% of the truth's and the
share more than 10% off (an unknown estimate counts as off), then the mean over the views and
the worst view. Both folders in the format of docs/depth.md ("Files").

    bench/depth_set_score.py ESTIMATE_DIR TRUTH_DIR

Needs python3-numpy and python3-opencv (Debian), as bench/heldout.py does.
"""
import json
import os
import struct
import sys

import cv2
import numpy as np


def text_chunks(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    chunks, i = {}, 8
    while i + 8 <= len(data):
        n = struct.unpack(">I", data[i:i + 4])[0]
        kind, body = data[i + 4:i + 8], data[i + 8:i + 8 + n]
        if kind == b"tEXt" and b"\0" in body:
            key, value = body.split(b"\0", 1)
            chunks[key.decode("latin-1")] = value.decode("latin-1")
        i += 12 + n
    return chunks


def depth_mm(path):
    chunks = text_chunks(path)
    if "depth_near_mm" not in chunks or "depth_far_mm" not in chunks:
        sys.exit(f"{path}: no depth range (depth_near_mm, depth_far_mm): not an lfcam depth map")
    near, far = float(chunks["depth_near_mm"]), float(chunks["depth_far_mm"])
    code = cv2.imread(path, cv2.IMREAD_UNCHANGED).astype(np.float64)
    depth = near + (code - 1) / 65534 * (far - near)
    depth[code == 0] = np.nan
    return depth


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    estimate, truth = sys.argv[1:]
    views = json.load(open(os.path.join(estimate, "depth.json")))["views"]
    within, off = [], []
    for v in views:
        e = depth_mm(os.path.join(estimate, v["file"]))
        t = depth_mm(os.path.join(truth, v["file"]))
        if e.shape != t.shape:
            sys.exit(f"{v['file']}: {e.shape} against the truth's {t.shape}")
        known = np.isfinite(t)
        rel = np.abs(e[known] - t[known]) / t[known]
        rel[~np.isfinite(rel)] = 1.0
        within.append(100 * np.mean(rel <= 0.01))
        off.append(100 * np.mean(rel > 0.1))
    print(f"{len(views)} views: {np.mean(within):.1f}% of samples within 1% of the true depth "
          f"(worst view {np.min(within):.1f}%), {np.mean(off):.1f}% more than 10% off")


if __name__ == "__main__":
    main()
