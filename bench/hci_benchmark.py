#!/usr/bin/env python3
"""Runs lfcam's depth on every scene of the HCI 4D Light Field Benchmark, as a submission.

    bench/hci_benchmark.py BENCHMARK OUT [--lfcam PATH] [--scenes NAME,...]
                           [--import-args "..."] [--depth-args "..."] [--pictures] [--json]

BENCHMARK is a copy of the benchmark as downloaded: a folder whose sub-folders (training/,
additional/, stratified/, test/, at any depth up to three) hold one scene each, its views named
input_Cam000.png ... input_Cam080.png beside parameters.cfg and, where the benchmark publishes
it, gt_disp_lowres.pfm; or a single scene's folder. Each scene is imported (`lfcam import`) and
its centre view's disparity estimated (`lfcam depth --disparity-pfm`), and OUT receives what the
benchmark's evaluation toolkit reads of a method (its submission layout):

    OUT/disp_maps/SCENE.pfm   the centre view's disparity (float32 PFM, the benchmark's sign and
                              units: px between neighbouring views, positive nearer)
    OUT/runtimes/SCENE.txt    the seconds it took from the scene's files: import and depth,
                              wall-clock, on this machine's cores
    OUT/scores.json           every scene's runtime, and, where gt_disp_lowres.pfm is present,
                              its BadPix(0.07, 0.03, 0.01) and MSE x 100 scored the way
                              bench/hci_score.py (the toolkit's definitions) scores them

With --pictures, each scored scene's centre view, truth, map and error are also drawn side by side
into OUT/pictures/SCENE.jpg, as `bench/hci_score.py --picture` draws them (python3-opencv).

And a table of the scores is printed. A scene that fails (a file lfcam refuses, a truth of another
size) is named with lfcam's reason; the other scenes still run, nothing of the failed scene is
left in OUT, and the script exits 1.
"""
import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hci_score  # noqa: E402  (beside this script)

FIRST_VIEW = "input_Cam000.png"
TRUTH = "gt_disp_lowres.pfm"


def find_scenes(root, depth=3):
    """{name: folder} of the folders holding input_Cam000.png, `root` itself or below it."""
    scenes = {}

    def visit(folder, level):
        if os.path.isfile(os.path.join(folder, FIRST_VIEW)):
            name = os.path.basename(os.path.normpath(folder))
            if name in scenes:
                raise ValueError(f"two scenes are named {name}: {scenes[name]} and {folder} "
                                 "(the toolkit names a scene's files by its folder's name)")
            scenes[name] = folder
            return
        if level == depth:
            return
        for entry in sorted(os.listdir(folder)):
            path = os.path.join(folder, entry)
            if os.path.isdir(path) and not entry.startswith("."):
                visit(path, level + 1)

    visit(root, 0)
    return scenes


def default_lfcam():
    here = os.path.dirname(os.path.abspath(__file__))
    built = os.path.join(here, "..", "build", "release", "lfcam")
    if os.access(built, os.X_OK):
        return os.path.normpath(built)
    return shutil.which("lfcam")


def write_atomically(path, text):
    temporary = path + ".partial"
    with open(temporary, "w") as f:
        f.write(text)
    os.replace(temporary, path)


def last_line(text):
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else "(no message)"


def centre_view(folder):
    """The benchmark's centre view: input_CamNNN.png halfway through the grid's files."""
    views = sorted(f for f in os.listdir(folder)
                   if f.startswith("input_Cam") and f.endswith(".png"))
    return os.path.join(folder, views[(len(views) - 1) // 2])


def run_scene(name, folder, lfcam, work, out, import_args, depth_args, pictures=False):
    """Imports and estimates one scene into `out`; returns its record (raises RuntimeError)."""
    lf = os.path.join(work, name + ".lf")
    depth_png = os.path.join(work, name + "_depth.png")
    pfm = os.path.join(out, "disp_maps", name + ".pfm")
    runtime = os.path.join(out, "runtimes", name + ".txt")
    drawn = os.path.join(out, "pictures", name + ".jpg")
    for stale in (pfm, runtime, drawn):  # a failed run leaves no earlier run's files as its own
        if os.path.exists(stale):
            os.remove(stale)
    truth_path = os.path.join(folder, TRUTH)
    truth = None
    if os.path.isfile(truth_path):  # read first: a truth that is not a PFM fails the scene now
        try:
            truth = hci_score.read_pfm(truth_path)
        except (OSError, ValueError) as e:
            raise RuntimeError(f"its truth: {e}")
    steps = [[lfcam, "import", folder, "--out", lf, "--quiet"] + import_args,
             [lfcam, "depth", lf, "--out", depth_png, "--disparity-pfm", pfm, "--quiet"] +
             depth_args]
    start = time.monotonic()
    for step in steps:
        done = subprocess.run(step, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            if os.path.exists(pfm):
                os.remove(pfm)
            raise RuntimeError(f"lfcam {step[1]}: {last_line(done.stderr or done.stdout)}")
    seconds = time.monotonic() - start
    write_atomically(runtime, f"{seconds:.3f}\n")
    record = {"folder": folder, "runtime_s": round(seconds, 3)}
    if truth is not None:
        try:
            estimate = hci_score.read_pfm(pfm)
            record["scores"] = hci_score.score(estimate, truth)
            if pictures:
                hci_score.picture(estimate, truth, 15, drawn, centre_view(folder))
        except (OSError, ValueError) as e:
            for written in (pfm, runtime, drawn):
                if os.path.exists(written):
                    os.remove(written)
            raise RuntimeError(f"not scored against {truth_path}: {e}")
    return record


def table(results):
    rows = [f"{'scene':<16} {'BadPix0.07':>10} {'BadPix0.03':>10} {'BadPix0.01':>10} "
            f"{'MSEx100':>8} {'seconds':>8}"]
    scored = []
    for name, r in results.items():
        s = r.get("scores")
        if s:
            scored.append(s)
            rows.append(f"{name:<16} {s['badpix_0.07']:>9.2f}% {s['badpix_0.03']:>9.2f}% "
                        f"{s['badpix_0.01']:>9.2f}% {s['mse_x100']:>8.3f} {r['runtime_s']:>8.1f}")
        else:
            rows.append(f"{name:<16} {'(no public truth)':>43} {r['runtime_s']:>8.1f}")
    if len(scored) > 1:
        mean = {k: sum(s[k] for s in scored) / len(scored)
                for k in ("badpix_0.07", "badpix_0.03", "badpix_0.01", "mse_x100")}
        rows.append(f"{'mean of ' + str(len(scored)):<16} {mean['badpix_0.07']:>9.2f}% "
                    f"{mean['badpix_0.03']:>9.2f}% {mean['badpix_0.01']:>9.2f}% "
                    f"{mean['mse_x100']:>8.3f}")
    return "\n".join(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("benchmark", help="the benchmark's folder, or one scene's")
    parser.add_argument("out", help="where disp_maps/, runtimes/ and scores.json go")
    parser.add_argument("--lfcam", help="the lfcam to run (default: build/release/lfcam, "
                        "else lfcam on PATH)")
    parser.add_argument("--scenes", help="only these scenes (comma-separated folder names)")
    parser.add_argument("--import-args", default="", help="more flags for lfcam import")
    parser.add_argument("--depth-args", default="", help="more flags for lfcam depth")
    parser.add_argument("--pictures", action="store_true",
                        help="also draw each scored scene's map beside its truth "
                        "(OUT/pictures/SCENE.jpg)")
    parser.add_argument("--json", action="store_true", help="print scores.json, not the table")
    args = parser.parse_args()
    if args.pictures:
        try:
            import cv2  # noqa: F401  (hci_score.picture draws with it)
        except ImportError:
            parser.error("--pictures draws with OpenCV's Python module: install python3-opencv")

    lfcam = args.lfcam or default_lfcam()
    if not lfcam or not os.access(lfcam, os.X_OK):
        parser.error(f"no lfcam to run ({args.lfcam or 'build/release/lfcam, or on PATH'}); "
                     "say which with --lfcam")
    if not os.path.isdir(args.benchmark):
        parser.error(f"{args.benchmark}: not a folder")
    try:
        scenes = find_scenes(args.benchmark)
    except (OSError, ValueError) as e:
        print(f"hci_benchmark: {e}", file=sys.stderr)
        return 1
    if not scenes:
        print(f"hci_benchmark: {args.benchmark}: no scene under it (a folder holding "
              f"{FIRST_VIEW} ...)", file=sys.stderr)
        return 1
    if args.scenes:
        wanted = [s for s in args.scenes.split(",") if s]
        unknown = [s for s in wanted if s not in scenes]
        if unknown:
            parser.error(f"--scenes: {', '.join(unknown)} not under {args.benchmark} "
                         f"(its scenes: {', '.join(sorted(scenes))})")
        scenes = {s: scenes[s] for s in wanted}

    for sub in ("disp_maps", "runtimes") + (("pictures",) if args.pictures else ()):
        os.makedirs(os.path.join(args.out, sub), exist_ok=True)
    results, failed = {}, {}
    with tempfile.TemporaryDirectory(prefix="lfcam_hci_") as work:
        for name in sorted(scenes):
            print(f"hci_benchmark: {name} ({scenes[name]})", file=sys.stderr, flush=True)
            try:
                results[name] = run_scene(name, scenes[name], lfcam, work, args.out,
                                          shlex.split(args.import_args),
                                          shlex.split(args.depth_args), args.pictures)
            except RuntimeError as e:
                failed[name] = str(e)
                print(f"hci_benchmark: {name} failed: {e}", file=sys.stderr, flush=True)
            for leftover in os.listdir(work):  # a scene's light field is not kept
                os.remove(os.path.join(work, leftover))
    report = {"lfcam": lfcam, "cores": os.cpu_count(), "import_args": args.import_args,
              "depth_args": args.depth_args, "scenes": results, "failed": failed}
    write_atomically(os.path.join(args.out, "scores.json"), json.dumps(report, indent=2) + "\n")
    if args.json:
        print(json.dumps(report, indent=2))
    elif results:
        print(table(results))
    if failed:
        print(f"hci_benchmark: {len(failed)} of {len(scenes)} scenes failed: "
              f"{', '.join(sorted(failed))}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
