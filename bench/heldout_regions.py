#!/usr/bin/env python3
"""Where the held-out views' errors lie (docs/fidelity.md, "Held-out views": where the depth
lookup loses to the mean of the nearest photographs).

Reads what bench/heldout.py left in WORK_DIR (heldout.json, the depth lookup's renders
r_R_C_depth.png) and the photographs in DATA_DIR, and prints, for the left-out cameras between
two kept rows, between two kept columns and diagonally between four:
- the median PSNR of the depth lookup and of the mean of the nearest photographs over the whole
  frame and over the frame without its top and bottom BAND rows (and without its left and right
  BAND columns);
- where the depth lookup's squared error exceeds the mean's, by distance from the nearest image
  edge (the excess MSE, per view, of the pixels that distance from that edge);
- each photograph's outermost row and column against the next one in (their mean ratio over the
  middle 80% of the edge), by the camera's grid row or column: a ratio that changes with the
  camera's place in the grid is a pattern fixed to the sensor that differs from view to view
  (the main lens vignetting a plenoptic camera's edge micro-images), which the mean of the
  nearest photographs interpolates where they sit and a renderer that follows the scene moves.

    bench/heldout_regions.py DATA_DIR WORK_DIR [--band N] [--json]
"""
import argparse
import json
import os
import statistics
import sys

import cv2
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ left in bench/
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from heldout import linear, srgb8  # noqa: E402 (the same light and encoding as the runs)


def psnr(mse):
    return float("inf") if mse == 0 else 10 * np.log10(255.0 ** 2 / mse)


def finite(x):
    """A PSNR for JSON: null where the frames are the same (infinite)."""
    return None if x == float("inf") else x


def read(path):
    img = cv2.imread(path)
    if img is None:
        sys.exit(f"{path}: not a readable image")
    return img[:, :, ::-1].astype(np.float64)


def direction(r, c):
    if r % 2 and c % 2:
        return "diagonal"
    return "between rows" if r % 2 else "between columns"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("work")
    ap.add_argument("--band", type=int, default=32, help="rows and columns left out at the edges")
    ap.add_argument("--json", action="store_true", help="print the figures as one JSON object")
    args = ap.parse_args()
    summary = os.path.join(args.work, "heldout.json")
    if not os.path.exists(summary):
        sys.exit(f"{summary}: missing (run bench/heldout.py {args.data} {args.work} first)")
    with open(summary) as f:
        views = json.load(f)["views"]
    if not views or "file" not in views[0]:
        sys.exit(f"{summary}: written by an older bench/heldout.py (no file names); run it again")

    band = args.band
    if band < 1:
        sys.exit(f"--band {band}: must be at least 1 sample")
    distances = [(lo, min(hi, band)) for lo, hi in [(0, 1), (1, 2), (2, 4), (4, 8), (8, 16),
                                                    (16, 32), (32, 64), (64, 128)] if lo < band]
    psnrs, excess, counts = {}, {}, {}
    edge_rows, edge_cols = {}, {}
    for v in views:
        r, c = v["camera"]
        truth = read(os.path.join(args.data, v["file"]))
        render = read(os.path.join(args.work, f"r_{r}_{c}_depth.png"))
        if render.shape != truth.shape:
            sys.exit(f"r_{r}_{c}_depth.png: {render.shape[1]}x{render.shape[0]}, its photograph "
                     f"{truth.shape[1]}x{truth.shape[0]}")
        mean = srgb8(np.mean([linear(read(os.path.join(args.data, n)))
                              for n in v["nearest_files"]], axis=0)).astype(np.float64)
        h, w = truth.shape[:2]
        if h <= 2 * band or w <= 2 * band:
            sys.exit(f"--band {band} leaves nothing of a {w}x{h} frame")
        e_depth = ((render - truth) ** 2).mean(axis=2)
        e_mean = ((mean - truth) ** 2).mean(axis=2)
        kind = direction(r, c)
        regions = {"whole": np.s_[:, :], "no top/bottom band": np.s_[band:-band, :],
                   "no left/right band": np.s_[:, band:-band]}
        for name, s in regions.items():
            psnrs.setdefault((kind, name), []).append(
                (psnr(e_depth[s].mean()), psnr(e_mean[s].mean())))
        yy, xx = np.mgrid[0:h, 0:w]
        to_edge = np.array([yy, h - 1 - yy, xx, w - 1 - xx])
        nearest_edge = to_edge.argmin(axis=0)
        dist = to_edge.min(axis=0)
        for lo, hi in distances:
            for e, edge in enumerate(["top", "bottom", "left", "right"]):
                sel = (dist >= lo) & (dist < hi) & (nearest_edge == e)
                key = (kind, edge, lo)
                excess[key] = excess.get(key, 0.0) + float((e_depth[sel] - e_mean[sel]).sum()) / (h * w)
        counts[kind] = counts.get(kind, 0) + 1
        grey = truth.sum(axis=2)
        mx, my = w // 10, h // 10
        inner_row, inner_col = grey[-2, mx:w - mx].mean(), grey[my:h - my, -2].mean()
        if inner_row > 0:  # a black edge says nothing
            edge_rows.setdefault(r, []).append(grey[-1, mx:w - mx].mean() / inner_row)
        if inner_col > 0:
            edge_cols.setdefault(c, []).append(grey[my:h - my, -1].mean() / inner_col)

    if args.json:
        out = {"views": len(views), "band": band, "directions": {},
               "last_row_ratio_by_grid_row":
                   {str(r): statistics.mean(v) for r, v in sorted(edge_rows.items())},
               "last_column_ratio_by_grid_column":
                   {str(c): statistics.mean(v) for c, v in sorted(edge_cols.items())}}
        for kind, n in counts.items():
            d = {"views": n, "median_psnr": {}, "excess_mse": {}}
            for name in ["whole", "no top/bottom band", "no left/right band"]:
                pairs = psnrs[(kind, name)]
                d["median_psnr"][name] = {"depth": finite(statistics.median(p[0] for p in pairs)),
                                          "mean": finite(statistics.median(p[1] for p in pairs))}
            for edge in ["top", "bottom", "left", "right"]:
                d["excess_mse"][edge] = {f"{lo}-{hi - 1}": excess[(kind, edge, lo)] / n
                                         for lo, hi in distances}
            out["directions"][kind] = d
        print(json.dumps(out, indent=1))
        return
    print(f"{len(views)} left-out views; bands of {band} samples")
    for kind in ["between columns", "between rows", "diagonal"]:
        if kind not in counts:
            continue
        print(f"{kind} ({counts[kind]} views): median PSNR, depth lookup / mean of the nearest")
        for name in ["whole", "no top/bottom band", "no left/right band"]:
            pairs = psnrs[(kind, name)]
            d = statistics.median(p[0] for p in pairs)
            m = statistics.median(p[1] for p in pairs)
            gain = statistics.median(p[0] - p[1] for p in pairs)
            print(f"  {name:20s} {d:6.2f} / {m:6.2f} dB   depth over mean {gain:+.2f} dB")
        print("  excess MSE of the depth lookup over the mean, per view, by distance from an edge:")
        for lo, hi in distances:
            cells = "  ".join(f"{edge} {excess[(kind, edge, lo)] / counts[kind]:+7.3f}"
                              for edge in ["top", "bottom", "left", "right"])
            print(f"    {lo:2d}-{hi - 1:<2d} samples: {cells}")
    print("each photograph's last row over the one before it, by the camera's grid row:")
    print("  " + "  ".join(f"{r}: {statistics.mean(v):.2f}" for r, v in sorted(edge_rows.items())))
    print("each photograph's last column over the one before it, by the camera's grid column:")
    print("  " + "  ".join(f"{c}: {statistics.mean(v):.2f}" for c, v in sorted(edge_cols.items())))


if __name__ == "__main__":
    main()
