#include "lfcam/core/staged_folder.h"

#include <fmt/format.h>
#include <unistd.h>

#include "lfcam/core/error.h"

namespace lfcam {

namespace fs = std::filesystem;

StagedFolder::StagedFolder(const fs::path& out)
    : out_(out.has_filename() ? out : out.parent_path()) {
  std::error_code ec;
  if (fs::exists(out_, ec) && (!fs::is_directory(out_, ec) || !fs::is_empty(out_, ec)))
    throw Error(fmt::format("{}: exists and is not an empty folder", out_.string()));
  staging_ = out_.string() + fmt::format(".partial-{}", ::getpid());
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) throw Error(fmt::format("{}: cannot create: {}", staging_.string(), ec.message()));
}

StagedFolder::~StagedFolder() {
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
}

void StagedFolder::Commit() {
  std::error_code ec;
  if (fs::exists(out_, ec)) fs::remove(out_, ec);
  fs::rename(staging_, out_, ec);
  if (ec)
    throw Error(
        fmt::format("{}: cannot move the export into place: {}", out_.string(), ec.message()));
  committed_ = true;
}

}  // namespace lfcam
