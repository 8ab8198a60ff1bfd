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

struct Opened {
  std::vector<void*> handles;  // kept open for the life of the process (FFmpeg keeps state)
  std::string sonames;
  std::string error;  // empty when every library opened
};

const Opened& Open() {
  static const Opened opened = [] {
    Opened o;
    for (const Library& l : Libraries()) {
      o.sonames += (o.sonames.empty() ? "" : ", ") + l.soname;
      void* handle = ::dlopen(l.soname.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle == nullptr) {
        const char* why = ::dlerror();
        o.error = fmt::format(
            "writing a video needs FFmpeg's {} (Debian's package {}: apt-get install {}): {}",
            l.soname, l.package, l.package, why ? why : "cannot be opened");
        return o;
      }
      o.handles.push_back(handle);
    }
    return o;
  }();
  return opened;
}

}  // namespace

void* FfmpegFunction(const char* name) {
  const Opened& opened = Open();
  if (!opened.error.empty()) throw Error(opened.error);
  for (void* handle : opened.handles)
    if (void* function = ::dlsym(handle, name)) return function;
  throw Error(
      fmt::format("this FFmpeg ({}) has no function {}: lfcam was built for another "
                  "version of it",
                  opened.sonames, name));
}

}  // namespace lfcam
