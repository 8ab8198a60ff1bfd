// The floor under any pinhole frame of a light field on this machine (bench/peer.sh): the time
// to read the bytes a 1024 x 1024 frame reads from its views and write the 8-bit RGB frame, from
// memory, on the threads a render uses, with no arithmetic at all. A 1024^2 pinhole of the paper's
// light field reads about 0.34 samples a pixel from each of four views (docs/benchmarks.md), so
// 4.3 MB in and 3.1 MB out. The caches are flushed before each frame, as a frame read from a
// 431-MB light field finds them.
//
//   lfcam_frame_floor [THREADS [FRAMES]]   prints "... median X ms, fastest Y ms"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::max(1, std::atoi(argv[1])) : 2;
  const int frames = argc > 2 ? std::max(1, std::atoi(argv[2])) : 60;
  constexpr std::size_t kPixels = 1024 * 1024;
  constexpr std::size_t kOut = kPixels * 3;                // the frame, 8-bit RGB
  constexpr std::size_t kIn = 4 * kPixels * 3 * 34 / 100;  // 4 views x 0.34 samples a pixel
  std::vector<unsigned char> in(kIn), out(kOut), flush(std::size_t(256) << 20);
  for (std::size_t i = 0; i < kIn; ++i) in[i] = static_cast<unsigned char>(i);
  std::vector<double> ms;
  unsigned sink = 0;
  for (int frame = 0; frame < frames; ++frame) {
    std::memset(flush.data(), frame, flush.size());
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    std::vector<unsigned> sums(std::size_t(threads), 0);
    for (int k = 0; k < threads; ++k)
      pool.emplace_back([&, k] {
        const std::size_t i0 = kIn * k / threads, i1 = kIn * (k + 1) / threads;
        const std::size_t o0 = kOut * k / threads, o1 = kOut * (k + 1) / threads;
        unsigned s = 0;
        for (std::size_t i = i0; i < i1; i += 64) s += in[i];  // one load a cache line
        std::memset(out.data() + o0, int(s & 0xff), o1 - o0);
        sums[std::size_t(k)] = s;
      });
    for (auto& t : pool) t.join();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
    for (const unsigned s : sums) sink += s;
  }
  std::sort(ms.begin(), ms.end());
  std::printf(
      "frame floor (%.1f MB read, %.1f MB written, %d threads, from memory, no arithmetic): "
      "median %.2f ms, fastest %.2f ms of %d (%u)\n",
      kIn / 1e6, kOut / 1e6, threads, ms[ms.size() / 2], ms.front(), frames, sink & 1u);
  return 0;
}
