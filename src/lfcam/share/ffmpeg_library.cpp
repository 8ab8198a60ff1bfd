#include "lfcam/share/ffmpeg_library.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <string>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// The libraries by the major versions of the headers lfcam was built with (their sonames), and
// the Debian packages that hold them. libavformat's handle also finds libavcodec's and
// libavutil's functions (dlsym searches a library's dependencies).
struct Library {
  std::string soname, package;
};
std::vector<Library> Libraries() {
  return {{fmt::format("libavformat.so.{}", LIBAVFORMAT_VERSION_MAJOR),
           fmt::format("libavformat{}", LIBAVFORMAT_VERSION_MAJOR)},
          {fmt::format("libswscale.so.{}", LIBSWSCALE_VERSION_MAJOR),
           fmt::format("libswscale{}", LIBSWSCALE_VERSION_MAJOR)}};
}

struct Loaded {
  FfmpegLibrary library;
  std::string error;  // empty when every function was found
};

Loaded Load() {
  Loaded loaded;
  const std::vector<Library> libraries = Libraries();
  std::vector<void*> handles;
  for (const Library& l : libraries) {
    // Kept open for the life of the process (FFmpeg keeps global state).
    void* handle = ::dlopen(l.soname.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = ::dlerror();
      loaded.error = fmt::format(
          "writing a video needs FFmpeg's {} (Debian's package {}: apt-get install {}): {}",
          l.soname, l.package, l.package, why ? why : "cannot be opened");
      return loaded;
    }
    handles.push_back(handle);
  }
  const auto find = [&](const char* name) -> void* {
    for (void* handle : handles)
      if (void* symbol = ::dlsym(handle, name)) return symbol;
    if (loaded.error.empty())
      loaded.error = fmt::format(
          "this FFmpeg ({}, {}) has no function {}: lfcam was built for "
          "another version of it",
          libraries[0].soname, libraries[1].soname, name);
    return nullptr;
  };
#define LFCAM_FFMPEG_FIND(name) \
  loaded.library.name = reinterpret_cast<decltype(loaded.library.name)>(find(#name));
  LFCAM_FFMPEG_FUNCTIONS(LFCAM_FFMPEG_FIND)
#undef LFCAM_FFMPEG_FIND
  return loaded;
}

}  // namespace

const FfmpegLibrary& Ffmpeg() {
  static const Loaded loaded = Load();
  if (!loaded.error.empty()) throw Error(loaded.error);
  return loaded.library;
}

}  // namespace lfcam
