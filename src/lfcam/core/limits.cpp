#include "lfcam/core/limits.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

double CgroupMemoryMax() {
  std::ifstream in("/sys/fs/cgroup/memory.max");
  std::string text;
  if (!(in >> text) || text == "max") return INFINITY;
  const auto v = ParseByteSize(text);
  return v ? *v : INFINITY;
}

}  // namespace

std::optional<double> ParseByteSize(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const std::string suffix = text.substr(used);
  double scale = 1;
  if (suffix == "K" || suffix == "k")
    scale = 1024.0;
  else if (suffix == "M" || suffix == "m")
    scale = 1024.0 * 1024;
  else if (suffix == "G" || suffix == "g")
    scale = 1024.0 * 1024 * 1024;
  else if (!suffix.empty())
    return std::nullopt;
  value *= scale;  // "1e308G" overflows here: refused below, never cast from infinity
  if (!std::isfinite(value) || value <= 0) return std::nullopt;
  return value;
}

std::uint64_t MemoryBudgetBytes() {
  if (const char* env = std::getenv("LFCAM_MEMORY_LIMIT")) {
    const auto v = ParseByteSize(env);
    if (!v)
      throw Error(
          fmt::format("LFCAM_MEMORY_LIMIT: '{}' is not a size (bytes, or with K, M, G)", env));
    return std::uint64_t(*v);
  }
  double memory = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGE_SIZE));
  memory = std::min(memory, CgroupMemoryMax());
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    memory = std::min(memory, double(limit.rlim_cur));
  return std::uint64_t(0.8 * memory);
}

std::string HumanBytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.1f} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.1f} MB", bytes / 1e6);
  if (bytes >= 1e3) return fmt::format("{:.1f} kB", bytes / 1e3);
  return fmt::format("{:.0f} bytes", bytes);
}

void RequireMemory(double bytes, const std::string& what) {
  const double budget = double(MemoryBudgetBytes());
  if (!(bytes <= budget))
    throw Error(
        fmt::format("{} needs {}, more than the memory limit of {} (80% of this "
                    "machine's memory, or LFCAM_MEMORY_LIMIT)",
                    what, HumanBytes(bytes), HumanBytes(budget)));
}

}  // namespace lfcam
