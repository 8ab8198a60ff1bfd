#!/usr/bin/env python3
"""Held-out views of any imported light field (docs/fidelity.md, "Held-out views").

Imports the whole folder once (any naming `lfcam import` reads: Stanford, Blender grid, HCI,
NAME_RR_CC, described) to learn which file is which camera and where each camera stood; keeps
every other camera (even grid rows and columns: a grid of twice the pitch), describes those in an
lfcam-views.json with the geometry the full import found (positions, focal length, rig and
zero-disparity plane), imports them, estimates their depth with `lfcam depth --all`, and renders
every left-out camera from them with `lfcam render --as-camera R,C` (R, C halfway between kept
cameras) with the paper's lookup and with the depth lookup. Each is compared over the whole frame
with the left-out real photograph, beside two baselines that need no renderer: the nearest kept
photograph, and the mean (in linear light) of the nearest kept photographs (2 or 4). PSNR over R,
G, B of the 8-bit sRGB images.

    bench/heldout.py DATA_DIR WORK_DIR [--lfcam PATH] [--limit N] [--import-args "..."]
                     [--depth-args "..."]
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import time

import cv2
import numpy as np


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


def psnr(a, b):
    d = a.astype(np.float64) - b.astype(np.float64)
    mse = float(np.mean(d * d))
    return float("inf") if mse == 0 else 10 * np.log10(255.0 ** 2 / mse)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("work")
    ap.add_argument("--lfcam", default="build/release/lfcam")
    ap.add_argument("--limit", type=int, default=0, help="only the first N left-out cameras")
    ap.add_argument("--import-args", default="", help="more flags for `lfcam import`")
    ap.add_argument("--depth-args", default="", help="more flags for `lfcam depth --all`")
    args = ap.parse_args()
    data = os.path.abspath(args.data)
    os.makedirs(args.work, exist_ok=True)
    extra = shlex.split(args.import_args)

    full_lf = os.path.join(args.work, "all.lf")
    full = json.loads(run([args.lfcam, "import", data, "--out", full_lf, "--json", "--quiet"] + extra))
    info = json.loads(run([args.lfcam, "info", full_lf, "--json"]))
    rows, cols = full["rows"], full["cols"]
    centre = {(c["row"], c["col"]): c["center_mm"] for c in info["cameras"]}
    files = {(v["row"], v["col"]): v["file"] for v in full["views"]}
    kept = [(r, c) for r in range(0, rows, 2) for c in range(0, cols, 2)]
    # Only the cameras between kept ones: in a grid of an even number of rows (or columns) the
    # last row lies beyond the last kept one, and a render there would be an extrapolation.
    last_row, last_col = kept[-1]
    out = [(r, c) for r in range(last_row + 1) for c in range(last_col + 1)
           if (r % 2, c % 2) != (0, 0)]
    beyond = rows * cols - len(kept) - len(out)
    if not out:
        sys.exit(f"{data}: a {rows}x{cols} grid has no camera between every other one to leave out")
    if args.limit:
        out = out[: args.limit]

    # The kept cameras, described with the geometry the full import found.
    sub = os.path.join(args.work, "kept")
    os.makedirs(sub, exist_ok=True)
    views = []
    for r, c in kept:
        link = os.path.join(sub, files[(r, c)])
        if not os.path.exists(link):
            os.symlink(os.path.join(data, files[(r, c)]), link)
        x, y, _ = centre[(r, c)]
        views.append({"row": r // 2, "col": c // 2, "file": files[(r, c)], "x_mm": x, "y_mm": y})
    description = {"format": "lfcam-views", "version": 2,
                   "rows": (rows + 1) // 2, "cols": (cols + 1) // 2,
                   "pitch_mm": 2 * full["pitch_mm"], "focal_px": full["focal_px"],
                   "rig": full["rig"], "views": views}
    if full["rig"] == "rectified":
        description["zero_disparity_distance_mm"] = full["zero_disparity_distance_mm"]
    with open(os.path.join(sub, "lfcam-views.json"), "w") as f:
        json.dump(description, f, indent=1)
    lf = os.path.join(args.work, "kept.lf")
    depth = os.path.join(args.work, "kept_depth")
    t0 = time.time()
    run([args.lfcam, "import", sub, "--out", lf, "--quiet"] + extra)
    if not os.path.exists(os.path.join(depth, "depth.json")):
        run([args.lfcam, "depth", lf, "--all", "--out", depth, "--quiet"]
            + shlex.split(args.depth_args))
    print(f"{data}: {rows}x{cols} views ({full['naming']}, {full['rig']} rig); {len(kept)} kept, "
          f"{len(out)} left out; kept imported and their depth estimated in "
          f"{time.time() - t0:.0f} s", flush=True)
    if beyond:
        print(f"  {beyond} cameras of the last row or column, beyond the last kept ones, not "
              "measured (a render there would extrapolate)")
    for assumed in full.get("assumed", []):
        print(f"  assumed: {assumed}")

    photo = {}

    def load(rc):
        if rc not in photo:
            photo[rc] = cv2.imread(os.path.join(data, files[rc]))[:, :, ::-1]
        return photo[rc]

    results = []
    for r, c in out:
        truth = load((r, c))
        dist = sorted(((r - kr) ** 2 + (c - kc) ** 2, (kr, kc)) for kr, kc in kept)
        nearest = [rc for d, rc in dist if d == dist[0][0]]
        at = f"{r / 2:g},{c / 2:g}"
        renders = {}
        for label, flags in [("paper", ["--interpolation", "quadrilinear"]),
                             ("depth", ["--interpolation", "depth", "--depth", depth])]:
            image = os.path.join(args.work, f"r_{r}_{c}_{label}.png")
            run([args.lfcam, "render", lf, "--as-camera", at, "--out", image, "--quiet"] + flags)
            renders[label] = cv2.imread(image)[:, :, ::-1]
        mean = srgb8(np.mean([linear(load(k)) for k in nearest], axis=0))
        row = {"camera": [r, c], "file": files[(r, c)], "neighbours": len(nearest),
               "nearest_files": [files[k] for k in nearest],
               "nearest": psnr(load(nearest[0]), truth), "mean": psnr(mean, truth),
               "paper": psnr(renders["paper"], truth), "depth": psnr(renders["depth"], truth)}
        results.append(row)
        print(json.dumps(row), flush=True)
    keys = ["nearest", "mean", "paper", "depth"]
    summary = {k: statistics.median(r[k] for r in results) for k in keys}
    summary["worst_depth_over_mean_db"] = min(r["depth"] - r["mean"] for r in results)
    summary["views"] = len(results)
    print("median PSNR, whole frame (dB): " + ", ".join(f"{k} {summary[k]:.2f}" for k in keys) +
          f"; depth lookup over the mean of the nearest: {summary['depth'] - summary['mean']:+.2f} "
          f"dB median, {summary['worst_depth_over_mean_db']:+.2f} dB worst")
    with open(os.path.join(args.work, "heldout.json"), "w") as f:
        json.dump({"data": data, "summary": summary, "views": results}, f, indent=1)


if __name__ == "__main__":
    main()
