#!/usr/bin/python3
"""The peer: the refocusing renderer a researcher writes in an afternoon with NumPy and OpenCV.

Shift-and-add: every view of the light field, decoded once to linear light at load, is warped
with cv2.warpAffine (bilinear) so that the plane of focus lines up, and the warped views are
averaged into the frame. It reads every one of the views once per frame. The geometry is
lfcam's (docs/conventions.md): the virtual camera at the array's centre looking along -n_ca,
f and d_o with focus breathing, each camera read along its own ray through the point in focus.

With --pinhole it renders the pinhole at the eye instead: the four views around the eye, weighted
by the eye's bilinear share of each camera (the paper's focal-plane lookup, as lfcam's pinhole).

Usage: bench/peer.py LIGHTFIELD.lf [--size 1024] [--focal-length 444] [--focus-distance 4000]
                     [--pinhole] [--runs 5] [--out peer.png]
Prints the median milliseconds per frame (after one warm-up frame). Needs Debian's python3-numpy
and python3-opencv; reads uncompressed srgb8 light fields (`lfcam simulate lightfield`'s
default).
"""
import argparse
import json
import mmap
import statistics
import struct
import sys
import time

import cv2
import numpy as np

FILM_MM = 56.0


def read_lightfield(path):
    with open(path, "rb") as f:
        data = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
    if data[:8] != b"\x89LFC\r\n\x1a\n":
        sys.exit(f"peer.py: {path}: not an lfcam light field")
    header_bytes, _, data_offset = struct.unpack_from("<QQQ", data, 16)
    header = json.loads(data[40:40 + header_bytes])
    if header["sample_type"] != "srgb8" or header["compression"] != "none":
        sys.exit(f"peer.py: {path}: needs an uncompressed srgb8 light field")
    return header, data, data_offset


def srgb_to_linear_table():
    c = np.arange(256, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4).astype(np.float32)


def camera_centers(slab, views):
    p_ca, u_ca, v_ca = (np.array(slab[k], dtype=np.float64) for k in ("p_ca", "u_ca", "v_ca"))
    rows, cols, pitch = slab["rows"], slab["cols"], slab["pitch_mm"]
    centers = {}
    for v in views:
        if "center" in v:
            centers[(v["row"], v["col"])] = np.array(v["center"], dtype=np.float64)
        else:
            centers[(v["row"], v["col"])] = (p_ca + (v["col"] + 0.5) * pitch * u_ca +
                                             (v["row"] + 0.5) * pitch * v_ca)
    return centers


def warp_matrices(header, size, f, d_o):
    """Per view, the 2x3 matrix from frame pixel (x, y) (y down) to view sample (k, l)."""
    slab = header["slab"]
    dims = header["dims"]
    n_s, n_t = dims["n_s"], dims["n_t"]
    p_ca, u_ca, v_ca, n_ca = (np.array(slab[k], dtype=np.float64)
                              for k in ("p_ca", "u_ca", "v_ca", "n_ca"))
    eye = p_ca + 0.5 * slab["cols"] * slab["pitch_mm"] * u_ca + \
        0.5 * slab["rows"] * slab["pitch_mm"] * v_ca
    win = slab["view_window"]
    st_o, x_axis, y_axis = (np.array(win[k], dtype=np.float64) for k in ("origin", "x_axis", "y_axis"))
    n_st = np.cross(x_axis, y_axis)
    s0, t0, s1, t1 = slab["st_domain"]
    film = f * d_o / (d_o - f)  # focus breathing: the film at d_i
    tan_half = 0.5 * FILM_MM / film

    def point_in_focus(x, y):  # frame pixel (x, y), y down
        i, j = x + 0.5, size - 1 - y + 0.5
        direction = -n_ca + tan_half * (2 * i / size - 1) * u_ca + tan_half * (2 * j / size - 1) * v_ca
        return eye + d_o * direction

    corners = [(0, 0), (1, 0), (0, 1)]
    points = [point_in_focus(x, y) for x, y in corners]
    matrices = {}
    for key, c in camera_centers(slab, header["views"]).items():
        kl = []
        for p in points:
            hit = c + (n_st @ (st_o - c)) / (n_st @ (p - c)) * (p - c)
            s = (hit - st_o) @ x_axis / win["width_mm"]
            t = (hit - st_o) @ y_axis / win["height_mm"]
            kl.append(((s - s0) * n_s / (s1 - s0) - 0.5, (t - t0) * n_t / (t1 - t0) - 0.5))
        (k00, l00), (k10, l10), (k01, l01) = kl
        matrices[key] = np.array([[k10 - k00, k01 - k00, k00], [l10 - l00, l01 - l00, l00]],
                                 dtype=np.float64)
    return matrices


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("lightfield")
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--focal-length", type=float, default=444.0)
    ap.add_argument("--focus-distance", type=float, default=4000.0)
    ap.add_argument("--pinhole", action="store_true",
                    help="the four views around the eye, bilinear (a pinhole), not all of them")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--out", default="")
    args = ap.parse_args()

    header, data, data_offset = read_lightfield(args.lightfield)
    dims = header["dims"]
    table = srgb_to_linear_table()
    views = []  # (matrix, weight, linear view)
    matrices = warp_matrices(header, args.size, args.focal_length, args.focus_distance)
    slab = header["slab"]
    # The eye (the array's centre) in grid units, camera (col, row) at (col, row): a pinhole
    # reads the four cameras around it, each by its bilinear share.
    ex, ey = 0.5 * slab["cols"] - 0.5, 0.5 * slab["rows"] - 0.5
    for v in header["views"]:
        if args.pinhole:
            share = max(0.0, 1 - abs(v["col"] - ex)) * max(0.0, 1 - abs(v["row"] - ey))
            if share == 0:
                continue
        else:
            share = 1.0 / len(header["views"])
        raw = np.frombuffer(data, dtype=np.uint8, count=dims["n_t"] * dims["n_s"] * 3,
                            offset=data_offset + v["offset"]).reshape(dims["n_t"], dims["n_s"], 3)
        views.append((matrices[(v["row"], v["col"])], np.float32(share), table[raw]))

    def frame():
        acc = np.zeros((args.size, args.size, 3), dtype=np.float32)
        for m, weight, view in views:
            acc += weight * cv2.warpAffine(view, m, (args.size, args.size),
                                           flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
                                           borderMode=cv2.BORDER_REPLICATE)
        return acc

    image = frame()  # warm-up
    times = []
    for _ in range(args.runs):
        start = time.perf_counter()
        image = frame()
        times.append((time.perf_counter() - start) * 1e3)
    print(f"peer (NumPy {np.__version__}, OpenCV {cv2.__version__}, {cv2.getNumThreads()} threads): "
          f"{len(views)} views into {args.size}x{args.size}: median {statistics.median(times):.1f} ms "
          f"of {args.runs}")
    if args.out:
        c = np.clip(image, 0, 1)
        srgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
        cv2.imwrite(args.out, cv2.cvtColor((srgb * 255 + 0.5).astype(np.uint8), cv2.COLOR_RGB2BGR))


if __name__ == "__main__":
    main()
