// The floor under any trigger skew measured with many agents on one machine
// (bench/capture.sh): N processes sleep until one common wall-clock time T, read the clock and
// record it, nothing else. The spread of what they read is what the machine's scheduler alone
// costs to wake N processes at once on its cores.
//
//   lfcam_wake_floor N   prints "N processes: skew X ms"
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  if (n < 1 || n > 10000) {
    std::fprintf(stderr, "usage: lfcam_wake_floor N (1..10000)\n");
    return 2;
  }
  auto* woke =
      static_cast<long long*>(mmap(nullptr, sizeof(long long) * std::size_t(n),
                                   PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0));
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  const long long t = (now.tv_sec + 1) * 1'000'000'000LL;  // the next whole second but one
  for (int i = 0; i < n; ++i) {
    if (fork() != 0) continue;
    prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
    const timespec at{time_t(t / 1'000'000'000), long(t % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_REALTIME, TIMER_ABSTIME, &at, nullptr) != 0) {
    }
    timespec read{};
    clock_gettime(CLOCK_REALTIME, &read);
    woke[i] = read.tv_sec * 1'000'000'000LL + read.tv_nsec - t;
    sleep(1);  // stay, as an agent does, rather than exit at once
    _exit(0);
  }
  while (wait(nullptr) > 0) {
  }
  const auto [lo, hi] = std::minmax_element(woke, woke + n);
  std::printf("%d processes: skew %.3f ms (first woke %.3f ms after T, last %.3f ms)\n", n,
              double(*hi - *lo) / 1e6, double(*lo) / 1e6, double(*hi) / 1e6);
  return 0;
}
