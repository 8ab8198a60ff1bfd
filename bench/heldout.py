#!/usr/bin/env python3
"""Held-out views of a real light field (docs/fidelity.md, "Held-out views of the shop").

Keeps every other camera of a Blender camera-grid data set (odd grid rows and columns: a grid of
twice the pitch), imports those with `lfcam import`, estimates their depth with `lfcam depth
--all`, and renders every left-out camera's position from them with the paper's lookup and with
the depth lookup (pinhole, the data set's own intrinsics). Each is compared with the left-out
real photograph, beside two baselines that need no renderer: the nearest kept photograph, and
the mean (in linear light) of the nearest kept photographs. PSNR over R, G, B of the 8-bit sRGB
images, over the pixels every render reaches.

    bench/heldout.py DATA_DIR WORK_DIR [--lfcam PATH] [--limit N]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time

import cv2
import numpy as np

NAME = re.compile(r"^(.*)_(\d+)_(\d+)_(-?[\d.]+)_(-?[\d.]+)_([\d.]+)_([\d.]+)\.(jpg|jpeg|png)$", re.I)


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{result.stdout}{result.stderr}")
    return result.stdout


def linear(img):
    x = img.astype(np.float64) / 255.0
    return np.where(x <= 0.04045, x / 12.92, ((x + 0.055) / 1.055) ** 2.4)


def srgb8(lin):
    lin = np.clip(lin, 0.0, 1.0)
    x = np.where(lin <= 0.0031308, lin * 12.92, 1.055 * lin ** (1 / 2.4) - 0.055)
    return np.clip(np.round(x * 255.0), 0, 255).astype(np.uint8)


def psnr(a, b, mask):
    d = (a.astype(np.float64) - b.astype(np.float64))[mask]
    mse = float(np.mean(d * d))
    return float("inf") if mse == 0 else 10 * np.log10(255.0 ** 2 / mse)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("work")
    ap.add_argument("--lfcam", default="build/release/lfcam")
    ap.add_argument("--limit", type=int, default=0, help="only the first N left-out cameras")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    cams = []
    for name in sorted(os.listdir(args.data)):
        m = NAME.match(name)
        if not m:
            continue
        row, col = int(m.group(2)), int(m.group(3))
        # lfcam's world frame (docs/format.md): x = the name's second number, y = minus its first.
        cams.append({"file": os.path.join(args.data, name), "row": row, "col": col,
                     "x": float(m.group(5)), "y": -float(m.group(4)),
                     "f": float(m.group(6)), "w": float(m.group(7))})
    kept = [c for c in cams if c["row"] % 2 == 1 and c["col"] % 2 == 1]
    out = [c for c in cams if not (c["row"] % 2 == 1 and c["col"] % 2 == 1)]
    if args.limit:
        out = out[: args.limit]
    sub = os.path.join(args.work, "kept")
    os.makedirs(sub, exist_ok=True)
    for c in kept:
        link = os.path.join(sub, os.path.basename(c["file"]))
        if not os.path.exists(link):
            os.symlink(os.path.abspath(c["file"]), link)
    lf = os.path.join(args.work, "kept.lf")
    depth = os.path.join(args.work, "kept_depth")
    t0 = time.time()
    if not os.path.exists(lf):
        run([args.lfcam, "import", sub, "--out", lf])
    info = json.loads(run([args.lfcam, "info", lf, "--json"]))
    st_distance = info["metadata"]["calibration"]["import"]["st_distance_mm"]
    if not os.path.exists(os.path.join(depth, "depth.json")):
        run([args.lfcam, "depth", lf, "--all", "--out", depth, "--quiet"])
    print(f"{len(kept)} kept, {len(out)} left out; kept imported and their depth estimated in "
          f"{time.time() - t0:.0f} s (st-plane {st_distance:.0f} mm)", flush=True)
    photos = {c["file"]: cv2.imread(c["file"])[:, :, ::-1] for c in cams}
    film = 56.0
    rows = []
    for c in out:
        truth = photos[c["file"]]
        h, w = truth.shape[:2]
        dist = sorted(((c["x"] - k["x"]) ** 2 + (c["y"] - k["y"]) ** 2, i) for i, k in enumerate(kept))
        nearest = [kept[i] for d, i in dist if d <= dist[0][0] * (1 + 1e-6)]
        z = info["cameras"][0]["center_mm"][2]
        common = ["--eye", f"{c['x']},{c['y']},{z}", "--look-at", f"{c['x']},{c['y']},0",
                  "--focal-length", f"{c['f'] * film / c['w']}", "--no-breathing",
                  "--size", f"{w}x{h}", "--quiet"]
        renders, masks = {}, []
        for label, extra in [("paper", ["--interpolation", "quadrilinear"]),
                             ("depth", ["--interpolation", "depth", "--depth", depth]),
                             ("depth_aa", ["--interpolation", "depth", "--depth", depth,
                                           "--antialias"])]:
            image = os.path.join(args.work, f"r_{c['row']}_{c['col']}_{label}.png")
            mask = os.path.join(args.work, f"m_{c['row']}_{c['col']}_{label}.png")
            run([args.lfcam, "render", lf, "--out", image, "--hit-mask", mask] + common + extra)
            renders[label] = cv2.imread(image)[:, :, ::-1]
            masks.append(cv2.imread(mask, cv2.IMREAD_GRAYSCALE) > 0)
        mask = np.logical_and.reduce(masks)
        mean = srgb8(np.mean([linear(photos[k["file"]]) for k in nearest], axis=0))
        row = {"camera": [c["row"], c["col"]], "neighbours": len(nearest),
               "nearest": psnr(photos[nearest[0]["file"]], truth, mask),
               "mean": psnr(mean, truth, mask),
               "paper": psnr(renders["paper"], truth, mask),
               "depth": psnr(renders["depth"], truth, mask),
               "depth_aa": psnr(renders["depth_aa"], truth, mask),
               "coverage": float(mask.mean())}
        rows.append(row)
        print(json.dumps(row), flush=True)
    keys = ["nearest", "mean", "paper", "depth", "depth_aa"]
    summary = {k: statistics.median(r[k] for r in rows) for k in keys}
    summary["mean_psnr"] = {k: statistics.mean(r[k] for r in rows) for k in keys}
    summary["views"] = len(rows)
    summary["depth_over_nearest_db"] = summary["depth"] - summary["nearest"]
    print("median PSNR (dB): " + ", ".join(f"{k} {summary[k]:.2f}" for k in keys))
    json.dump({"summary": summary, "views": rows}, open(os.path.join(args.work, "heldout.json"), "w"),
              indent=1)


if __name__ == "__main__":
    main()
