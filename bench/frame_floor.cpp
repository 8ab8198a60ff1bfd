// The floor under any pinhole frame of a light field on this machine (bench/peer.sh): the time
// to read the bytes a 1024 x 1024 frame reads from its views and write the frame, from memory,
// on the threads a render uses, with no arithmetic at all. A 1024^2 pinhole of the paper's
// light field reads about 0.34 samples a pixel from each of four views (docs/benchmarks.md), so
// 4.3 MB in; out, 3.1 MB as 8-bit RGB or 17.8 MB as lfcam's result. The caches are flushed before
// each frame, as a frame read from a 431-MB light field finds them.
//
//   lfcam_frame_floor [THREADS [FRAMES]]   prints "... median X ms, fastest Y ms", twice
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

namespace {

// The median and fastest of `frames` frames that each read `in` (one load a cache line) and
// write `out_bytes` bytes a pixel of a 1024^2 frame, on `threads` threads, the caches flushed
// before each.
struct Floor {
  double median_ms, fastest_ms;
};
Floor Measure(const std::vector<unsigned char>& in, std::size_t out_bytes, int threads, int frames,
              std::vector<unsigned char>& flush, unsigned& sink) {
  constexpr std::size_t kPixels = 1024 * 1024;
  std::vector<unsigned char> out(kPixels * out_bytes);
  std::vector<double> ms;
  for (int frame = 0; frame < frames; ++frame) {
    std::memset(flush.data(), frame, flush.size());
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    std::vector<unsigned> sums(std::size_t(threads), 0);
    for (int k = 0; k < threads; ++k)
      pool.emplace_back([&, k] {
        const std::size_t i0 = in.size() * k / threads, i1 = in.size() * (k + 1) / threads;
        const std::size_t o0 = out.size() * k / threads, o1 = out.size() * (k + 1) / threads;
        unsigned s = 0;
        for (std::size_t i = i0; i < i1; i += 64) s += in[i];
        std::memset(out.data() + o0, int(s & 0xff), o1 - o0);
        sums[std::size_t(k)] = s;
      });
    for (auto& t : pool) t.join();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
    for (const unsigned s : sums) sink += s;
  }
  std::sort(ms.begin(), ms.end());
  return {ms[ms.size() / 2], ms.front()};
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::max(1, std::atoi(argv[1])) : 2;
  const int frames = argc > 2 ? std::max(1, std::atoi(argv[2])) : 60;
  constexpr std::size_t kPixels = 1024 * 1024;
  constexpr std::size_t kIn = 4 * kPixels * 3 * 34 / 100;  // 4 views x 0.34 samples a pixel
  std::vector<unsigned char> in(kIn), flush(std::size_t(256) << 20);
  for (std::size_t i = 0; i < kIn; ++i) in[i] = static_cast<unsigned char>(i);
  unsigned sink = 0;
  // An 8-bit RGB frame; and what lfcam's CPU renderer returns (render/cpu_renderer.h: the frame
  // in linear float RGB, each pixel's count as int32 and its hit mask, 17 bytes a pixel), which
  // the NumPy peer's float32 frame (12 bytes a pixel) compares with.
  for (const auto& [label, bytes] :
       {std::pair{"an 8-bit RGB frame", std::size_t(3)},
        std::pair{"lfcam's result (float RGB, count, mask)", std::size_t(17)}}) {
    const Floor f = Measure(in, bytes, threads, frames, flush, sink);
    std::printf(
        "frame floor, %s (%.1f MB read, %.1f MB written, %d threads, from memory, no "
        "arithmetic): median %.2f ms, fastest %.2f ms of %d\n",
        label, kIn / 1e6, double(kPixels * bytes) / 1e6, threads, f.median_ms, f.fastest_ms,
        frames);
  }
  volatile unsigned keep = sink;  // the loads' sums, so that the reads stay
  (void)keep;
  return 0;
}
