#!/usr/bin/env python3
"""Scores a disparity map the way the HCI 4D Light Field Benchmark's evaluation toolkit does.

    bench/hci_score.py ESTIMATE.pfm GT.pfm [--border 15] [--silhouettes] [--bands] [--json]
    bench/hci_score.py --registration-cost GT.pfm [--border 15] [--json]
    bench/hci_score.py ESTIMATE.pfm GT.pfm --picture OUT.png [--view CENTRE.png]

Both are PFM files of the centre view's disparity (float32, one channel, rows stored from the
bottom up as PFM does; the benchmark's gt_disp_lowres.pfm, and `lfcam depth --disparity-pfm`).
Over the view less a border of 15 pixels (the toolkit's), it prints BadPix(0.07), BadPix(0.03),
BadPix(0.01) (the percentage of pixels whose |estimate - truth| exceeds the threshold) and
MSE x 100 (the mean squared error times 100). A file that is not such a PFM, or maps of
different sizes, are refused with the reason; the PFM is read here, not by lfcam.

--silhouettes also splits the error by where it lies against the truth's depth edges (a jump of
more than 0.3 px between a pixel and one of its 8 neighbours): on the near side of an edge (the
pixel is the nearer of the two), on its far side, and elsewhere; for each, its pixels, its share
of MSE x 100 (the three add up to the whole) and its big errors (over 0.3 px), counting those
that make the near side smaller than the truth has it (thinned: the estimate farther there) and
the far side's that make it larger (fattened: the estimate nearer). Most of a good map's MSE lies
in the first two (docs/depth.md, "Where `hci-antinous`' silhouette error is now").

--bands says where BadPix(0.07)'s pixels lie: on the truth's depth edges (the pixels either side
of a jump, as above), on the near or the far side 1-3 and 4-9 pixels from them (the side of the
nearest edge pixel, counted in steps to any of the 8 neighbours; a pixel as near to both sides
counts for the near one), and 10 pixels or more from any; for each, its pixels, those more than
0.07 px off (and their share of all such), and the median error, signed (negative: the estimate
farther than the truth). A map that is right away from the edges and thins or fattens them has
its bad pixels in the first rows; one biased on a whole surface shows it in the median
(docs/depth.md, "Where BadPix0.07's pixels lie").

--picture OUT.png also draws the truth, the estimate (the same colours for the same disparity:
turbo over the truth's 1st to 99th percentile, widened by a tenth, 0.1 px at least) and the error |estimate -
truth| (black 0, white 0.3 px or more; the border the score leaves out drawn dimmed), side by
side, with the photograph first when --view gives the centre view (docs/depth.md's picture of
`hci-antinous`). It needs OpenCV's Python module (python3-opencv).

--registration-cost scores the truth against itself moved by one whole row and by one whole
column: what a map registered to a pixel grid one sample away from the truth's would lose, all of
it at the truth's depth edges and slopes. An estimate that follows the photographs pays a share of
it in proportion to how far the truth's grid lies from theirs (docs/depth.md).
"""
import argparse
import json
import sys

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        if kind not in (b"Pf", b"PF"):
            raise ValueError(f"{path}: not a PFM (first line {kind[:16]!r})")
        channels = 1 if kind == b"Pf" else 3
        try:
            width, height = (int(v) for v in f.readline().split())
            scale = float(f.readline().strip())
        except ValueError as e:
            raise ValueError(f"{path}: a PFM header needs 'width height' and a scale ({e})")
        if width <= 0 or height <= 0 or width * height > 1 << 28:
            raise ValueError(f"{path}: {width}x{height} is not a size")
        dtype = "<f4" if scale < 0 else ">f4"
        data = np.frombuffer(f.read(), dtype=dtype)
    if data.size != width * height * channels:
        raise ValueError(f"{path}: {data.size} values for {width}x{height}x{channels}")
    if channels != 1:
        raise ValueError(f"{path}: a disparity map has one channel, this PFM has three")
    # PFM rows run from the bottom of the image up.
    return np.flipud(data.reshape(height, width)).astype(np.float64)


def score(estimate, truth, border=15):
    if estimate.shape != truth.shape:
        raise ValueError(f"the maps differ in size: {estimate.shape[1]}x{estimate.shape[0]} "
                         f"against the truth's {truth.shape[1]}x{truth.shape[0]}")
    if min(truth.shape) <= 2 * border:
        raise ValueError(f"a {truth.shape[1]}x{truth.shape[0]} map has nothing inside a "
                         f"{border}-pixel border")
    inner = (slice(border, -border), slice(border, -border)) if border > 0 else np.s_[:, :]
    error = estimate[inner] - truth[inner]
    error = np.where(np.isfinite(error), error, np.inf)  # an unknown pixel is a bad one
    out = {f"badpix_{t:.2f}": float(100.0 * np.mean(np.abs(error) > t)) for t in (0.07, 0.03, 0.01)}
    finite = np.isfinite(error)
    out["mse_x100"] = float(100.0 * np.mean(np.where(finite, error, 0.0) ** 2)) if finite.all() \
        else float("inf")
    out["pixels"] = int(error.size)
    return out


def neighbourhood(values, reduce):
    """The min or max (`reduce`) of each pixel's 3 x 3 neighbourhood, the edge repeated."""
    h, w = values.shape
    padded = np.pad(values, 1, mode="edge")
    shifts = [padded[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)]
    return reduce(np.stack(shifts), axis=0)


def edge_sides(truth, jump):
    """The pixels on the near side of the truth's depth edges (a jump of more than `jump` to one
    of its 8 neighbours, positive disparity nearer), and those on the far side alone."""
    near = truth - neighbourhood(truth, np.min) > jump
    return near, (neighbourhood(truth, np.max) - truth > jump) & ~near


def silhouettes(estimate, truth, border=15, jump=0.3, big=0.3):
    """The error split by the side of the truth's depth edges (positive disparity is nearer)."""
    near, far = edge_sides(truth, jump)
    inner = (slice(border, -border), slice(border, -border)) if border > 0 else np.s_[:, :]
    error = (estimate - truth)[inner]
    error = np.where(np.isfinite(error), error, np.inf)
    total = error.size

    def region(mask):
        e = error[mask[inner]]
        squared = float(np.sum(e[np.isfinite(e)] ** 2)) if np.isfinite(e).all() else float("inf")
        return {"pixels": int(e.size), "mse_x100": 100.0 * squared / total,
                "big": int(np.sum(np.abs(e) > big))}, e

    out = {"jump_px": jump, "big_px": big}
    out["near_side"], e = region(near)
    out["near_side"]["thinned"] = int(np.sum(e < -big))
    out["far_side"], e = region(far)
    out["far_side"]["fattened"] = int(np.sum(e > big))
    out["elsewhere"], _ = region(~near & ~far)
    return out


def steps_to(mask, most):
    """Each pixel's distance from `mask` in steps to one of its 8 neighbours, up to `most` (most
    + 1 beyond)."""
    steps = np.full(mask.shape, most + 1)
    reached = mask.copy()
    steps[reached] = 0
    for k in range(1, most + 1):
        reached = neighbourhood(reached, np.max)
        steps[reached & (steps > most)] = k
    return steps


BANDS = (("on an edge", "edge"), ("near side, 1-3 px", "near_1_3"),
         ("near side, 4-9 px", "near_4_9"), ("far side, 1-3 px", "far_1_3"),
         ("far side, 4-9 px", "far_4_9"), ("10 px or more from an edge", "beyond"))


def bands(estimate, truth, border=15, jump=0.3, threshold=0.07):
    """BadPix(threshold)'s pixels by side of, and distance from, the truth's depth edges."""
    near_edge, far_edge = edge_sides(truth, jump)
    to_near, to_far = steps_to(near_edge, 9), steps_to(far_edge, 9)
    distance = np.minimum(to_near, to_far)
    near = to_near <= to_far
    masks = {"edge": distance == 0,
             "near_1_3": near & (distance >= 1) & (distance <= 3),
             "near_4_9": near & (distance >= 4) & (distance <= 9),
             "far_1_3": ~near & (distance >= 1) & (distance <= 3),
             "far_4_9": ~near & (distance >= 4) & (distance <= 9),
             "beyond": distance >= 10}
    inner = (slice(border, -border), slice(border, -border)) if border > 0 else np.s_[:, :]
    error = (estimate - truth)[inner]
    bad = ~(np.abs(error) <= threshold)  # an unknown pixel is a bad one
    out = {"jump_px": jump, "threshold_px": threshold, "bad": int(bad.sum())}
    for _, key in BANDS:
        m = masks[key][inner]
        e = error[m]
        e = e[np.isfinite(e)]
        out[key] = {"pixels": int(m.sum()), "bad": int(bad[m].sum()),
                    "median_error": float(np.median(e)) if e.size else 0.0}
    return out


def band_lines(b):
    lines = [f"  where BadPix{b['threshold_px']:.2f}'s {b['bad']} pixels lie (the truth's depth "
             f"edges: jumps over {b['jump_px']} px; the median error signed, negative farther):"]
    for label, key in BANDS:
        r = b[key]
        share = 100.0 * r["bad"] / b["bad"] if b["bad"] else 0.0
        lines.append(f"    {label + ':':<28}{r['pixels']:>8} pixels {r['bad']:>7} bad "
                     f"({share:4.1f}% of them), median error {r['median_error']:+.4f}")
    return lines


def moved(truth, rows, cols):
    """The map moved by whole rows (down) and columns (right), its edge repeated."""
    h, w = truth.shape
    y = np.clip(np.arange(h) - rows, 0, h - 1)
    x = np.clip(np.arange(w) - cols, 0, w - 1)
    return truth[np.ix_(y, x)]


def line(result):
    return (f"BadPix0.07 {result['badpix_0.07']:.2f}%  BadPix0.03 {result['badpix_0.03']:.2f}%  "
            f"BadPix0.01 {result['badpix_0.01']:.2f}%  MSEx100 {result['mse_x100']:.3f}")


def silhouette_lines(s):
    n, f, o = s["near_side"], s["far_side"], s["elsewhere"]
    return [f"  near side of the truth's depth edges: {n['pixels']} pixels, MSEx100 "
            f"{n['mse_x100']:.3f}, {n['big']} big errors ({n['thinned']} thinned: the estimate "
            "farther)",
            f"  far side: {f['pixels']} pixels, MSEx100 {f['mse_x100']:.3f}, {f['big']} big "
            f"errors ({f['fattened']} fattened: the estimate nearer)",
            f"  elsewhere: {o['pixels']} pixels, MSEx100 {o['mse_x100']:.3f}, {o['big']} big "
            "errors"]


def picture(estimate, truth, border, out, view=None):
    """The truth, the estimate and the error side by side (and the photograph first), to look at."""
    import cv2  # only here: scoring needs NumPy alone

    lo, hi = np.percentile(truth[np.isfinite(truth)], [1, 99])
    pad = max(0.1 * (hi - lo), 0.1)  # at least 0.1 px: a flat truth (one depth) has a scale too
    lo, hi = lo - pad, hi + pad

    def coloured(d):
        grey = np.clip((np.nan_to_num(d, nan=lo) - lo) / (hi - lo) * 255, 0, 255)
        return cv2.applyColorMap(grey.astype(np.uint8), cv2.COLORMAP_TURBO)

    error = np.abs(estimate - truth)
    error = np.where(np.isfinite(error), error, 0.3)
    error = cv2.cvtColor((np.clip(error / 0.3, 0, 1) * 255).astype(np.uint8), cv2.COLOR_GRAY2BGR)
    inside = np.zeros(truth.shape, bool)
    inside[border:truth.shape[0] - border, border:truth.shape[1] - border] = True
    error[~inside] //= 3
    panels = [coloured(truth), coloured(estimate), error]
    if view is not None:
        photo = cv2.imread(view, cv2.IMREAD_COLOR)
        if photo is None:
            raise ValueError(f"{view}: not an image OpenCV reads")
        if photo.shape[:2] != truth.shape:
            raise ValueError(f"{view}: {photo.shape[1]}x{photo.shape[0]}, the maps are "
                             f"{truth.shape[1]}x{truth.shape[0]}")
        panels.insert(0, photo)
    gap = np.full((truth.shape[0], 8, 3), 255, np.uint8)
    row = [panels[0]]
    for p in panels[1:]:
        row += [gap, p]
    if not cv2.imwrite(out, np.hstack(row)):
        raise OSError(f"{out}: could not be written")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("maps", nargs="+", metavar="PFM",
                        help="ESTIMATE.pfm GT.pfm, or GT.pfm with --registration-cost")
    parser.add_argument("--registration-cost", action="store_true",
                        help="score the truth against itself moved one row and one column")
    parser.add_argument("--silhouettes", action="store_true",
                        help="also split the error by the side of the truth's depth edges")
    parser.add_argument("--bands", action="store_true",
                        help="also say where BadPix0.07's pixels lie against the truth's edges")
    parser.add_argument("--border", type=int, default=15)
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--picture", metavar="OUT.png",
                        help="also draw the truth, the estimate and the error side by side")
    parser.add_argument("--view", metavar="CENTRE.png",
                        help="with --picture: the centre view's photograph, drawn first")
    args = parser.parse_args()
    wanted = 1 if args.registration_cost else 2
    if len(args.maps) != wanted:
        parser.error(f"expected {'GT.pfm' if wanted == 1 else 'ESTIMATE.pfm GT.pfm'}, "
                     f"got {len(args.maps)} files")
    if (args.silhouettes or args.bands or args.picture) and args.registration_cost:
        parser.error("--silhouettes, --bands and --picture take an estimate: not with "
                     "--registration-cost")
    if args.view and not args.picture:
        parser.error("--view is drawn in --picture's file: give --picture too")
    try:
        if args.registration_cost:
            truth = read_pfm(args.maps[0])
            result = {"one_row": score(moved(truth, 1, 0), truth, args.border),
                      "one_column": score(moved(truth, 0, 1), truth, args.border)}
        else:
            estimate, truth = read_pfm(args.maps[0]), read_pfm(args.maps[1])
            result = score(estimate, truth, args.border)
            if args.silhouettes:
                result["silhouettes"] = silhouettes(estimate, truth, args.border)
            if args.bands:
                result["bands"] = bands(estimate, truth, args.border)
            if args.picture:
                picture(estimate, truth, args.border, args.picture, args.view)
    except (OSError, ValueError) as e:
        print(f"hci_score: {e}", file=sys.stderr)
        return 1
    if args.json:
        print(json.dumps(result, indent=2))
    elif args.registration_cost:
        for name, label in (("one_row", "moved one row:   "), ("one_column", "moved one column:")):
            print(f"{label} {line(result[name])}")
    else:
        print(f"{line(result)}  ({result['pixels']} pixels, {args.border}-pixel border left out)")
        if args.silhouettes:
            print("\n".join(silhouette_lines(result["silhouettes"])))
        if args.bands:
            print("\n".join(band_lines(result["bands"])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
