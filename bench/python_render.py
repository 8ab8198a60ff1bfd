#!/usr/bin/python3
"""`import lfcam` against `lfcam render`: the same frames, in one run, one after the other.

For each frame (the paper's full-aperture refocus through every camera, and a pinhole), times
  - `lfcam render ... --repeat N` (the command's own median of the render, file writing left out),
  - lfcam.render(lf, linear=True, ...) (the same render, returned as a float32 array),
  - lfcam.render(lf, ...) (the same, encoded to uint8 sRGB as the command writes it),
and prints the medians and the module's overhead against the command. The module must add
nothing but its call: its target is within 5% of the command (docs/python.md).

Usage: bench/python_render.py LIGHTFIELD.lf [--runs 9] [--lfcam build/release/lfcam]
Needs the module on PYTHONPATH (build/release/python) or python3-lfcam installed.
"""
import argparse
import re
import statistics
import subprocess
import sys
import time

import lfcam


def command_median_ms(binary, lightfield, flags, runs):
    out = subprocess.run([binary, "render", lightfield, "--out", "/tmp/lfcam_python_bench.png",
                          "--repeat", str(runs), "--quiet", *flags],
                         capture_output=True, text=True, check=True).stdout
    return float(re.search(r"; ([0-9.]+) ms.*\(median of", out).group(1))


def module_median_ms(lf, keywords, runs, linear):
    lfcam.render(lf, linear=linear, **keywords)  # warm-up
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        lfcam.render(lf, linear=linear, **keywords)
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("lightfield")
    ap.add_argument("--runs", type=int, default=9)
    ap.add_argument("--lfcam", default="build/release/lfcam")
    args = ap.parse_args()
    lf = lfcam.open(args.lightfield)
    print(f"{lf!r} from {args.lightfield}; module {lfcam.__file__}")
    frames = [
        ("d_l 256, cameras integrator (every view)",
         dict(size=1024, focal_length=444, focus_distance=4000, aperture=256,
              integrator="cameras"),
         ["--size", "1024", "--focal-length", "444", "--focus-distance", "4000",
          "--aperture", "256", "--integrator", "cameras"]),
        ("pinhole (focal-plane lookup)",
         dict(size=1024, focal_length=444, focus_distance=4000, interpolation="focal-plane"),
         ["--size", "1024", "--focal-length", "444", "--focus-distance", "4000",
          "--interpolation", "focal-plane"]),
    ]
    for name, keywords, flags in frames:
        command = command_median_ms(args.lfcam, args.lightfield, flags, args.runs)
        linear = module_median_ms(lf, keywords, args.runs, linear=True)
        encoded = module_median_ms(lf, keywords, args.runs, linear=False)
        print(f"{name}: lfcam render {command:.2f} ms; lfcam.render(linear=True) {linear:.2f} ms "
              f"({100 * (linear / command - 1):+.1f}%); lfcam.render (uint8 sRGB) "
              f"{encoded:.2f} ms ({100 * (encoded / command - 1):+.1f}%, the encoding included)")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
