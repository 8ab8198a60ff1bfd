#pragma once
// libjpeg's errors as lfcam handles them (core/jpeg_region.cpp, node/jpeg_preview.cpp):
// libjpeg reports an error through a callback that must not return, so it jumps back to the
// caller's setjmp with the message, and the caller throws once no libjpeg frame is on the stack.
// Warnings (data libjpeg can decode around) stay quiet, except a premature end of the file: the
// rows after it would be grey, so `truncated` is set for the caller to refuse.
//
// No OpenCV here: the node agent (built without it) uses this too.
#include <csetjmp>
#include <cstdio>
// jpeglib.h needs FILE and size_t declared first.
#include <jerror.h>
#include <jpeglib.h>

namespace lfcam {

struct LibjpegErrors {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
  bool truncated;

  // Installs the handlers; returns the manager for `cinfo.err` (of any libjpeg object).
  jpeg_error_mgr* install() {
    jpeg_std_error(&base);
    base.error_exit = [](j_common_ptr cinfo) {
      auto* e = reinterpret_cast<LibjpegErrors*>(cinfo->err);
      (*cinfo->err->format_message)(cinfo, e->message);
      std::longjmp(e->jump, 1);
    };
    base.emit_message = [](j_common_ptr cinfo, int level) {
      if (level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF)
        reinterpret_cast<LibjpegErrors*>(cinfo->err)->truncated = true;
    };
    message[0] = '\0';
    truncated = false;
    return &base;
  }
};

}  // namespace lfcam
