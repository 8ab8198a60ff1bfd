#pragma once
// Parsing helpers for flag values ("X,Y,Z", "WxH"); errors name the flag.
#include <string>
#include <utility>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/geometry.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/slab.h"

namespace lfcam::cli {

// Runs f(); an lfcam::Error it throws is a bad flag value: rethrown as UsageError naming the flag.
template <typename F>
auto FlagValue(const std::string& flag, F&& f) {
  try {
    return f();
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(flag + ": " + e.what());
  }
}

std::vector<double> ParseNumbers(const std::string& flag, const std::string& text,
                                 std::size_t count, char separator = ',');
Vec3 ParseVec3(const std::string& flag, const std::string& text);
// "N" (square) or "WxH", each 1..max_side.
std::pair<int, int> ParseSize(const std::string& flag, const std::string& text, int max_side);

// "S0,T0,S1,T1": the sampled st domain, S1 > S0, T1 > T0, each within +-kMaxStDomainBound.
StDomain ParseStDomain(const std::string& flag, const std::string& text);
// "shared" (false) or "views" (true: each view in its own st window).
bool ParseStWindows(const std::string& flag, const std::string& text);

// An output folder (`export --out`, `depth --all --out`, `simulate lightfield --depth-out`): new,
// or an empty folder; otherwise UsageError naming `flag`.
void RequireNewOrEmptyFolder(const std::string& flag, const std::string& path);

// "none" or "zstd": how a light field file's samples are stored (`build`, `import`).
Compression ParseCompression(const std::string& flag, const std::string& text);

}  // namespace lfcam::cli
