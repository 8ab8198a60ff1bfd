#pragma once
// The resource limits every reader and command checks before it allocates or loops: one place,
// so that commands agree (docs/robustness.md lists them for users).
#include <cstdint>
#include <optional>
#include <string>

namespace lfcam {

inline constexpr int kMaxImageSide = 16384;         // rendered, read and written images
inline constexpr int kMaxViewsPerSide = 4096;       // light field camera grid, a side
inline constexpr int kMaxStSamplesPerSide = 65536;  // st samples per view, a side
inline constexpr int kMaxLensSamples = 1 << 17;     // n_ls, rays a pixel
inline constexpr int kMaxOracleSamples = 1 << 16;   // oracle samples a pixel
inline constexpr int kMaxThreads = 1024;
inline constexpr double kMaxStDomainBound = 1000.0;  // |s|, |t| of the sampled st domain
inline constexpr std::uint64_t kMaxLightFieldBytes = std::uint64_t(1) << 36;  // 64 GiB of samples
inline constexpr int kMaxJsonDepth = 64;  // nesting of any JSON lfcam reads
inline constexpr std::uint64_t kMaxJsonBytes = 16u << 20;

// The most memory one allocation of bulk data (samples, decoded images) may take: 80% of the
// smaller of the machine's physical memory, the cgroup's memory.max and RLIMIT_AS, or the
// LFCAM_MEMORY_LIMIT environment variable (bytes, or with a K, M or G suffix) when it is set.
std::uint64_t MemoryBudgetBytes();

// "123", "64M", "2G" (K, M, G: powers of 1024) as bytes; nullopt when the text is not a positive,
// finite size. How LFCAM_MEMORY_LIMIT is read.
std::optional<double> ParseByteSize(const std::string& text);

// Throws lfcam::Error when `bytes` (computed in double so that nothing wraps) exceeds the
// budget: "<what> needs 6.6 GB, more than the memory limit of 3.0 GB (...)".
void RequireMemory(double bytes, const std::string& what);

// "6.6 GB", "512.0 MB": sizes for messages.
std::string HumanBytes(double bytes);

}  // namespace lfcam
