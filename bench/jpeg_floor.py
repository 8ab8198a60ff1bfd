#!/usr/bin/env python3
"""How far a JPEG photograph is from the image it was compressed from (docs/fidelity.md,
"What limits the shop's held-out views").

A held-out photograph stored as JPEG carries its own compression error, which no render from
other photographs can predict in full: it bounds the PSNR any render can measure against it.
The original is gone, so the error is estimated: the decoded photograph, moved by a few pixels
so that its 8 x 8 blocks no longer fall on the encoder's grid, is compressed again at the file's
own quality (read from its quantisation tables), and the error of that second compression is
measured (the mean over four such moves). Because the decoded photograph has already lost what
the first compression removed, the estimate runs optimistic; `--calibrate PNG...` measures by how
much on lossless images of your choosing (each compressed once at the same quality, the true
first-compression PSNR beside the estimate made from the result).

    bench/jpeg_floor.py JPEG... [--calibrate PNG...]
"""
import argparse
import statistics
import sys

import cv2
import numpy as np

# The IJG's base luminance table (Annex K of the JPEG standard), in zigzag order as DQT stores it.
BASE_LUMA_ZIGZAG = [16, 11, 12, 14, 12, 10, 16, 14, 13, 14, 18, 17, 16, 19, 24, 40, 26, 24, 22,
                    22, 24, 49, 35, 37, 29, 40, 58, 51, 61, 60, 57, 51, 56, 55, 64, 72, 92, 78, 64,
                    68, 87, 69, 55, 56, 80, 109, 81, 87, 95, 98, 103, 104, 103, 62, 77, 113, 121,
                    112, 100, 120, 92, 101, 103, 99]
MOVES = [(1, 2), (3, 3), (5, 1), (2, 6)]


def luma_table(data, name):
    """The first quantisation table (8-bit precision) of a JPEG file's bytes."""
    at = 2
    while at + 4 <= len(data):
        if data[at] != 0xFF:
            break
        marker, length = data[at + 1], int.from_bytes(data[at + 2:at + 4], "big")
        if marker == 0xDB:
            precision = data[at + 4] >> 4
            if precision != 0:
                sys.exit(f"{name}: 16-bit quantisation tables are not handled")
            return list(data[at + 5:at + 5 + 64])
        if marker == 0xDA:
            break
        at += 2 + length
    sys.exit(f"{name}: no quantisation table before the image data (not a baseline JPEG?)")


def ijg_quality(table):
    """The IJG quality whose scaled base table is nearest to `table` (the libjpeg scaling)."""
    def scaled(q):
        s = 5000 // q if q < 50 else 200 - 2 * q
        return [min(255, max(1, (b * s + 50) // 100)) for b in BASE_LUMA_ZIGZAG]
    errors = {q: sum(abs(a - b) for a, b in zip(scaled(q), table)) for q in range(1, 101)}
    best = min(errors, key=errors.get)
    return best, errors[best]


def compress(image, quality):
    ok, data = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, quality])
    assert ok
    return cv2.imdecode(data, cv2.IMREAD_COLOR)


def psnr_of_mse(mse):
    return 10 * np.log10(255.0 ** 2 / mse)


def estimate(decoded, quality):
    """PSNR of a second, off-grid compression of `decoded` at `quality` (mean error of MOVES)."""
    errors = []
    for dy, dx in MOVES:
        moved = decoded[dy:, dx:]
        d = moved.astype(np.float64) - compress(moved, quality)
        errors.append(float(np.mean(d * d)))
    return psnr_of_mse(statistics.mean(errors))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("jpegs", nargs="+")
    ap.add_argument("--calibrate", nargs="*", default=[], metavar="PNG")
    args = ap.parse_args()
    qualities, estimates = [], []
    for name in args.jpegs:
        with open(name, "rb") as f:
            data = f.read()
        if data[:2] != b"\xff\xd8":
            sys.exit(f"{name}: not a JPEG file")
        quality, mismatch = ijg_quality(luma_table(data, name))
        decoded = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_COLOR)
        if decoded is None:
            sys.exit(f"{name}: the JPEG does not decode")
        est = estimate(decoded, quality)
        note = "" if mismatch == 0 else f" (tables {mismatch} off the IJG's: not an IJG encoder?)"
        print(f"{name}: quality {quality}{note}; estimated compression error {est:.2f} dB PSNR")
        qualities.append(quality)
        estimates.append(est)
    print(f"median of {len(estimates)}: {statistics.median(estimates):.2f} dB "
          f"(quality {statistics.median(qualities):g})")
    quality = int(statistics.median(qualities))
    for name in args.calibrate:
        image = cv2.imread(name, cv2.IMREAD_COLOR)
        if image is None:
            sys.exit(f"{name}: not an image")
        once = compress(image, quality)
        d = image.astype(np.float64) - once
        first = psnr_of_mse(float(np.mean(d * d)))
        est = estimate(once, quality)
        print(f"calibration {name}: first compression {first:.2f} dB, estimated {est:.2f} dB "
              f"(the estimate {est - first:+.2f} dB off)")


if __name__ == "__main__":
    main()
