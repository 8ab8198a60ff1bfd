#pragma once
// Work that waits on the network, not on a core: `count` jobs on up to `max_threads` threads of
// their own (TBB's pool is sized for the cores and would queue blocking requests behind one
// another). Exceptions inside `job` are the caller's to catch.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace lfcam {

// Requests to nodes at once (status, configure, capture): one thread each, up to this many.
inline constexpr std::size_t kMaxRequestThreads = 128;

template <typename Job>
void RunConcurrently(std::size_t count, std::size_t max_threads, Job&& job) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) job(i);
  };
  const std::size_t threads = std::min(count, std::max<std::size_t>(1, max_threads));
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
  if (threads > 0) worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace lfcam
