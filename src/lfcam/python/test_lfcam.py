"""`import lfcam` under pytest (ctest runs it as Python.ModuleTests; docs/python.md).

The module is checked against the command it sits beside: the same light field rendered by
`lfcam render` (LFCAM_CLI) and by lfcam.render must be the same picture, byte for byte, and
every mistake must come back as a Python exception carrying lfcam's message, never a crash.
"""
import json
import os
import struct
import subprocess
import zlib

import numpy as np
import pytest

import lfcam

CLI = os.environ.get("LFCAM_CLI", "lfcam")


def run_cli(*args):
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def read_png_rgb8(path):
    """An 8-bit RGB PNG as an H x W x 3 array (what `lfcam render` writes), with zlib alone."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 2, 0)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(height, 1 + 3 * width)
    out = np.zeros((height, 3 * width), np.int32)
    previous = np.zeros(3 * width, np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        row = np.zeros(3 * width, np.int32)
        for x in range(3 * width):
            left = row[x - 3] if x >= 3 else 0
            up = previous[x]
            up_left = previous[x - 3] if x >= 3 else 0
            if kind == 0:
                predictor = 0
            elif kind == 1:
                predictor = left
            elif kind == 2:
                predictor = up
            elif kind == 3:
                predictor = (left + up) // 2
            else:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else up_left)
            row[x] = (line[x] + predictor) & 0xFF
        out[y] = row
        previous = row
    return out.reshape(height, width, 3).astype(np.uint8)


@pytest.fixture(scope="module")
def lightfield_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("lf") / "small.lf"
    run_cli("simulate", "lightfield", "--out", path, "--grid", "4x4", "--st-res", "96x88",
            "--quiet")
    return path


@pytest.fixture(scope="module")
def lf(lightfield_path):
    return lfcam.open(str(lightfield_path))


def test_views_are_the_files_samples_without_a_copy(lf):
    assert (lf.rows, lf.cols, lf.n_t, lf.n_s) == (4, 4, 88, 96)
    assert lf.shape == (4, 4, 88, 96, 3) and lf.sample_type == "srgb8"
    views, samples = lf.views, lf.samples
    assert views.dtype == np.uint8 and views.shape == lf.shape
    assert not views.flags.writeable
    assert np.shares_memory(views, samples)
    # No copy: every call is an array over the same memory, which the arrays do not own.
    address = samples.__array_interface__["data"][0]
    assert lf.samples.__array_interface__["data"][0] == address
    assert not samples.flags.owndata and not views.flags.owndata
    # A view as an image is its st rows top first.
    assert np.array_equal(lf.view(1, 2), views[1, 2])
    assert np.array_equal(views[1, 2][::-1], samples[1, 2])
    with pytest.raises(ValueError):
        views[0, 0, 0, 0, 0] = 1


def test_geometry_and_cameras(lf):
    slab = lf.slab
    assert slab["uv"]["rows"] == 4 and slab["uv"]["cols"] == 4
    assert slab["uv"]["pitch_mm"] == pytest.approx(28.0)
    assert slab["separation_mm"] > 0
    step = lf.camera_center(0, 1) - lf.camera_center(0, 0)
    assert np.linalg.norm(step) == pytest.approx(28.0)
    camera = lf.camera(0, 0)
    assert (camera["width"], camera["height"]) == (96, 88)
    assert camera["world_from_camera"].shape == (4, 4)
    assert np.allclose(camera["world_from_camera"][:3, 3], lf.camera_center(0, 0))
    assert isinstance(lf.metadata, dict)
    with pytest.raises(lfcam.UsageError, match="view \\(4, 0\\)"):
        lf.camera(4, 0)


@pytest.mark.parametrize("keywords, flags", [
    (dict(size=(80, 60)), ["--size", "80x60"]),
    (dict(size=64, aperture=40.0, focus_distance=3500, lens_rate=2),
     ["--size", "64", "--aperture", "40", "--focus-distance", "3500", "--lens-rate", "2"]),
    (dict(size=(72, 56), aperture=60, integrator="cameras", eye=(150, 120, 0)),
     ["--size", "72x56", "--aperture", "60", "--integrator", "cameras", "--eye", "150,120,0"]),
    (dict(size=48, look_at=(100, 200, -3000), focal_length=300, no_breathing=True),
     ["--size", "48", "--look-at", "100,200,-3000", "--focal-length", "300", "--no-breathing"]),
])
def test_render_is_lfcam_renders_picture(lf, lightfield_path, tmp_path, keywords, flags):
    out = tmp_path / "cli.png"
    run_cli("render", lightfield_path, "--out", out, "--quiet", *flags)
    image = lfcam.render(lf, **keywords)
    assert image.dtype == np.uint8 and image.shape[2] == 3
    assert np.array_equal(image, read_png_rgb8(out))


def test_render_in_linear_light(lf):
    linear = lfcam.render(lf, size=32, linear=True)
    encoded = lfcam.render(lf, size=32)
    assert linear.dtype == np.float32 and linear.shape == (32, 32, 3)
    srgb = np.where(linear <= 0.0031308, 12.92 * linear,
                    1.055 * np.power(np.maximum(linear, 0), 1 / 2.4) - 0.055)
    assert np.abs(np.round(np.clip(srgb, 0, 1) * 255) - encoded).max() <= 1


def test_mistakes_are_python_exceptions_with_lfcams_messages(lf, tmp_path):
    with pytest.raises(lfcam.UsageError, match="'focal_lenght' is not a keyword of render"):
        lfcam.render(lf, focal_lenght=50)
    with pytest.raises(ValueError, match="focal_length: -3 must be a positive number of mm"):
        lfcam.render(lf, focal_length=-3)
    with pytest.raises(lfcam.UsageError, match="focus_distance"):
        lfcam.render(lf, focus_distance=10)
    with pytest.raises(lfcam.UsageError, match="eye: expected 3 numbers"):
        lfcam.render(lf, eye=(1, 2))
    with pytest.raises(TypeError, match="eye"):
        lfcam.render(lf, eye=object())
    with pytest.raises(TypeError, match="eye: expected numbers"):
        lfcam.render(lf, eye=("a", "b", "c"))
    with pytest.raises(lfcam.UsageError, match="integrator"):
        lfcam.render(lf, integrator="magic")
    with pytest.raises(lfcam.UsageError, match="size"):
        lfcam.render(lf, size=(0, 10))
    with pytest.raises(lfcam.UsageError, match="camera"):
        lfcam.render(lf, camera=str(tmp_path / "missing.json"))
    with pytest.raises(lfcam.UsageError, match="threads"):
        lfcam.render(lf, threads=10**30)
    with pytest.raises(lfcam.UsageError, match="focal_length does not go with as_camera"):
        lfcam.render(lf, focal_length=50, as_camera=(1, 2))
    with pytest.raises(lfcam.UsageError, match="as_camera: the light field records no camera"):
        lfcam.render(lf, as_camera=(1, 2))
    with pytest.raises(lfcam.Error, match="no such file"):
        lfcam.open(str(tmp_path / "missing.lf"))
    broken = tmp_path / "broken.lf"
    broken.write_bytes(b"LFCAM" + bytes(100))
    with pytest.raises(lfcam.Error, match="broken.lf"):
        lfcam.open(str(broken))
    assert issubclass(lfcam.UsageError, lfcam.Error)
    assert issubclass(lfcam.Error, RuntimeError)


def test_depth_of_a_view(lf):
    result = lfcam.depth(lf, 1, 1, near=2000, far=8000)
    depth = result["depth"]
    assert depth.shape == (lf.n_t, lf.n_s) and depth.dtype == np.float32
    known = np.isfinite(depth)
    assert known.mean() > 0.5
    assert np.all((depth[known] >= 2000 - 1) & (depth[known] <= 8000 + 1))
    assert result["confidence"].shape == depth.shape
    with pytest.raises(lfcam.UsageError, match="near and far go together"):
        lfcam.depth(lf, near=1000)


def test_export_writes_what_lfcam_export_writes(lf, tmp_path):
    report = lfcam.export(lf, str(tmp_path / "views"), "png-views")
    assert report["views"] == 16
    cameras = json.load(open(tmp_path / "views" / "cameras.json"))
    assert len(cameras["views"]) == 16
    with pytest.raises(lfcam.Error):
        lfcam.export(lf, str(tmp_path / "views"), "png-views")  # not empty: refused
    with pytest.raises(lfcam.UsageError, match="format 'gif'"):
        lfcam.export(lf, str(tmp_path / "other"), "gif")


def test_read_session(tmp_path):
    session = tmp_path / "session"
    run_cli("simulate", "capture", "--out", session, "--grid", "2x2", "--sensor", "160x120",
            "--shots", "1", "--supersampling", "1", "--quiet")
    manifest = lfcam.read_session(str(session))
    assert manifest["grid"]["rows"] == 2
    kinds = [shot["kind"] for shot in manifest["shots"]]
    assert "scene" in kinds and "intrinsics" in kinds
    with pytest.raises(lfcam.Error, match="manifest"):
        lfcam.read_session(str(tmp_path))


def write_png_rgb8(path, image):
    """An H x W x 3 uint8 array as a PNG (filter 0), with zlib alone."""
    height, width, _ = image.shape
    raw = b"".join(b"\x00" + image[y].tobytes() for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + \
            struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" +
                     chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                     chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def test_import_views_is_lfcam_import(tmp_path):
    # Plenoptic-style views named NAME_RR_CC (row 1 at the top), a rectified rig: each view is
    # stored sample for sample, so the imported views are the photographs themselves.
    folder = tmp_path / "views"
    folder.mkdir()
    rng = np.random.default_rng(26)
    photos = {}
    for r in range(1, 4):
        for c in range(1, 4):
            photos[r, c] = rng.integers(0, 256, (24, 32, 3), dtype=np.uint8)
            write_png_rgb8(folder / f"scene_{r:02d}_{c:02d}.png", photos[r, c])
    lf, summary = lfcam.import_views(str(folder), pitch_mm=2.5, focal_px=40)
    assert summary["rig"] == "rectified" and summary["naming"] == "unit-grid"
    assert (lf.rows, lf.cols, lf.n_t, lf.n_s) == (3, 3, 24, 32)
    assert summary["pitch_mm"] == pytest.approx(2.5)
    # lfcam's row 0 is the bottom row: the file's row 3.
    assert np.array_equal(lf.view(0, 0), photos[3, 1])
    assert np.array_equal(lf.view(2, 2), photos[1, 3])
    # Saved, it is what `lfcam import` writes from the same folder and flags.
    lf.save(str(tmp_path / "python.lf"))
    run_cli("import", folder, "--out", tmp_path / "cli.lf", "--pitch-mm", "2.5", "--focal-px",
            "40", "--quiet")
    assert np.array_equal(lfcam.open(str(tmp_path / "python.lf")).samples,
                          lfcam.open(str(tmp_path / "cli.lf")).samples)
    with pytest.raises(lfcam.UsageError, match="'aperture' is not a keyword of import_views"):
        lfcam.import_views(str(folder), aperture=3)
    with pytest.raises(lfcam.UsageError, match="st_res: a rectified rig"):
        lfcam.import_views(str(folder), st_res=(16, 12))
    with pytest.raises(lfcam.Error, match="missing"):
        lfcam.import_views(str(tmp_path / "missing"))


SHARED = os.path.join(os.environ.get("LFCAM_SOURCE_DIR", "."), "..", "shared", "data")


@pytest.mark.skipif(not os.path.isdir(os.path.join(SHARED, "hci-antinous")),
                    reason="../shared/data/hci-antinous is not here")
def test_a_real_benchmark_scene_imports_and_renders():
    lf, summary = lfcam.import_views(os.path.join(SHARED, "hci-antinous"))
    assert (lf.rows, lf.cols) == (9, 9) and summary["naming"] == "hci"
    centre = lfcam.render(lf, as_camera=(4, 4))
    # Rendered as its own centre camera, a rectified view comes back as the photograph.
    assert np.abs(centre.astype(int) - lf.view(4, 4).astype(int)).mean() < 1.0


def test_the_guides_example_runs(lightfield_path, capsys):
    guide = open(os.path.join(os.environ.get("LFCAM_SOURCE_DIR", "."), "docs", "python.md")).read()
    example = guide.split("## Refocus in five lines")[1].split("```python\n")[1].split("```")[0]
    exec(example.replace('"paper.lf"', repr(str(lightfield_path))), {})
    printed = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in printed] == ["3400", "4200", "5200"]
    assert all("(512, 512, 3) uint8" in line for line in printed)
