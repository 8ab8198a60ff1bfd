#!/usr/bin/python3
"""What each way of compressing a light field video costs (issue 24): the .lfv's own per-frame
zstd of the views (what `lfcam build` writes) against per-view video streams through FFmpeg's
libraries (Debian's libavcodec, reached through OpenCV's FFmpeg backend): H.264 (libx264, lossy,
its default quality) and FFV1 (lossless). Reads an uncompressed .lfv (build --compress none),
encodes every view's frames as one stream per view, and prints bytes per light field frame,
encode and decode seconds, and the PSNR of the lossy streams.

  bench/video_codecs.py VIDEO.lfv [--views N] [--frames N]

Random access costs differ too: a zstd frame is read alone; an H.264 stream decodes from its last
keyframe (OpenCV's writer puts one every 12 frames by default)."""
import argparse, json, os, struct, sys, tempfile, time

import cv2
import numpy as np


def frames_of(path):
    """(offset, bytes) of each frame's embedded .lf in a .lfv."""
    with open(path, 'rb') as f:
        pre = f.read(64)
        assert pre[:8] == b'\x89LFV\r\n\x1a\n', 'not a light field video'
        first = struct.unpack_from('<Q', pre, 32)[0]
        size = os.fstat(f.fileno()).st_size
        at, out = first, []
        while at + 64 <= size:
            f.seek(at)
            r = f.read(64)
            if r[:8] != b'LFVFRAME':
                break
            n = struct.unpack_from('<Q', r, 32)[0]
            out.append((at + 64, n))
            at = (at + 64 + n + 4095) // 4096 * 4096
        return out


def views_of(path, offset):
    """The views of an uncompressed embedded .lf: (rows, cols, n_s, n_t, bytes per view, data)."""
    with open(path, 'rb') as f:
        f.seek(offset)
        pre = f.read(40)
        header_bytes, data_offset = struct.unpack_from('<Q', pre, 16)[0], struct.unpack_from('<Q', pre, 32)[0]
        header = json.loads(f.read(header_bytes))
        assert header['compression'] == 'none', 'build the video with --compress none'
        d = header['dims']
        view_bytes = d['n_s'] * d['n_t'] * 3
        f.seek(offset + data_offset)
        data = f.read(view_bytes * d['rows'] * d['cols'])
        return d, view_bytes, data


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('video')
    ap.add_argument('--views', type=int, default=100)
    ap.add_argument('--frames', type=int, default=30)
    a = ap.parse_args()
    frames = frames_of(a.video)[:a.frames]
    d, view_bytes, _ = views_of(a.video, frames[0][0])
    n_views = min(a.views, d['rows'] * d['cols'])
    w, h = d['n_s'], d['n_t']
    # views[v][k]: view v of frame k (BGR for OpenCV)
    views = [[] for _ in range(n_views)]
    for off, _ in frames:
        _, _, data = views_of(a.video, off)
        for v in range(n_views):
            img = np.frombuffer(data, np.uint8, view_bytes, v * view_bytes).reshape(h, w, 3)
            views[v].append(cv2.cvtColor(np.ascontiguousarray(img[::-1]), cv2.COLOR_RGB2BGR))
    raw = len(frames) * n_views * view_bytes
    print(f'{len(frames)} frames of {n_views} views of {w}x{h}: raw {raw / len(frames) / 1e6:.1f} MB a frame')
    tmp = tempfile.mkdtemp()
    for name, fourcc, ext in (('H.264 (libx264)', 'avc1', 'mp4'), ('FFV1 (lossless)', 'FFV1', 'mkv')):
        t0 = time.time()
        total = 0
        for v in range(n_views):
            p = os.path.join(tmp, f'v{v}.{ext}')
            wr = cv2.VideoWriter(p, cv2.CAP_FFMPEG, cv2.VideoWriter_fourcc(*fourcc), 30, (w, h))
            if not wr.isOpened():
                print(f'{name}: this OpenCV cannot write it'); break
            for img in views[v]:
                wr.write(img)
            wr.release()
            total += os.path.getsize(p)
        else:
            enc = time.time() - t0
            t0 = time.time()
            se, n = 0.0, 0
            for v in range(n_views):
                cap = cv2.VideoCapture(os.path.join(tmp, f'v{v}.{ext}'), cv2.CAP_FFMPEG)
                k = 0
                while True:
                    ok, img = cap.read()
                    if not ok:
                        break
                    if k < len(views[v]):
                        se += float(np.mean((img.astype(np.float64) - views[v][k]) ** 2))
                        n += 1
                    k += 1
            dec = time.time() - t0
            psnr = 10 * np.log10(255 ** 2 / (se / max(n, 1))) if se > 0 else float('inf')
            print(f'{name}: {total / len(frames) / 1e6:.2f} MB a frame ({raw / total:.1f}x), '
                  f'encode {enc / len(frames) * 1e3:.0f} ms a frame, decode all {dec / len(frames) * 1e3:.0f} ms a frame, '
                  f'PSNR {psnr:.1f} dB')
        for f_ in os.listdir(tmp):
            os.remove(os.path.join(tmp, f_))
    os.rmdir(tmp)


if __name__ == '__main__':
    main()
