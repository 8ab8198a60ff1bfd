#include "lfcam/gpu/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

std::string EglErrorName(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return fmt::format("EGL error 0x{:x}", error);
  }
}

bool HasClientExtension(const char* name) { return epoxy_has_egl_extension(EGL_NO_DISPLAY, name); }

// A display to try, and what to call it in messages.
struct Candidate {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string name;
  bool software = false;
};

// (Filled member by member: GCC 12 warns falsely on a braced Candidate pushed back.)
void Add(std::vector<Candidate>& out, EGLDisplay display, const std::string& name, bool software) {
  if (display == EGL_NO_DISPLAY) return;
  Candidate& c = out.emplace_back();
  c.display = display;
  c.name = name;
  c.software = software;
}

std::vector<Candidate> Candidates() {
  std::vector<Candidate> out;
  if (HasClientExtension("EGL_EXT_device_enumeration") &&
      HasClientExtension("EGL_EXT_platform_device")) {
    EGLint count = 0;
    if (eglQueryDevicesEXT(0, nullptr, &count) && count > 0) {
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
      eglQueryDevicesEXT(count, devices.data(), &count);
      for (EGLint i = 0; i < count; ++i) {
        const char* extensions = eglQueryDeviceStringEXT(devices[std::size_t(i)], EGL_EXTENSIONS);
        const bool software =
            extensions != nullptr && std::strstr(extensions, "EGL_MESA_device_software") != nullptr;
        const EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
        Add(out, display, fmt::format("EGL device {}", i), software);
      }
    }
  }
  if (HasClientExtension("EGL_MESA_platform_surfaceless")) {
    const EGLDisplay display =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    Add(out, display, "Mesa's surfaceless platform", true);
  }
  Add(out, eglGetDisplay(EGL_DEFAULT_DISPLAY), "the default EGL display", false);
  return out;
}

// A GL 4.3 core context on `display` (initialised), or EGL_NO_CONTEXT with the reason.
EGLContext CreateContext(EGLDisplay display, std::string* why) {
  if (!eglBindAPI(EGL_OPENGL_API)) {
    *why = "no desktop OpenGL API (" + EglErrorName(eglGetError()) + ")";
    return EGL_NO_CONTEXT;
  }
  EGLConfig config = nullptr;
  if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                             EGL_NONE};
    EGLint found = 0;
    if (!eglChooseConfig(display, wanted, &config, 1, &found) || found < 1) {
      *why = "no OpenGL configuration";
      return EGL_NO_CONTEXT;
    }
  }
  if (!epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
    *why = "no surfaceless contexts (EGL_KHR_surfaceless_context)";
    return EGL_NO_CONTEXT;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    *why = "no OpenGL 4.3 core context (" + EglErrorName(eglGetError()) + ")";
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    *why = "the context could not be made current (" + EglErrorName(eglGetError()) + ")";
    eglDestroyContext(display, context);
    return EGL_NO_CONTEXT;
  }
  return context;
}

std::string GlString(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

bool IsSoftwareRenderer(const std::string& renderer) {
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (renderer.find(name) != std::string::npos) return true;
  return false;
}

}  // namespace

std::unique_ptr<GlContext> GlContext::Create(bool prefer_hardware) {
  std::vector<Candidate> candidates = Candidates();
  if (candidates.empty())
    throw Error("no OpenGL: EGL offers no display (is libEGL with a driver installed?)");
  std::stable_sort(
      candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
        return prefer_hardware ? (!a.software && b.software) : (a.software && !b.software);
      });
  std::vector<std::string> failures;
  for (const Candidate& candidate : candidates) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(candidate.display, &major, &minor)) {
      failures.push_back(candidate.name + ": " + EglErrorName(eglGetError()));
      continue;
    }
    std::string why;
    const EGLContext context = CreateContext(candidate.display, &why);
    if (context == EGL_NO_CONTEXT) {
      failures.push_back(candidate.name + ": " + why);
      continue;
    }
    std::unique_ptr<GlContext> gl(new GlContext());
    gl->display_ = candidate.display;
    gl->context_ = context;
    gl->device_.renderer = GlString(GL_RENDERER);
    gl->device_.vendor = GlString(GL_VENDOR);
    gl->device_.version = GlString(GL_VERSION);
    gl->device_.software = IsSoftwareRenderer(gl->device_.renderer);
    if (epoxy_gl_version() < 43) {
      failures.push_back(candidate.name + ": OpenGL " + gl->device_.version + " is older than 4.3");
      continue;  // the destructor releases it
    }
    return gl;
  }
  std::string message = "no OpenGL 4.3 core context could be made through EGL:";
  for (const std::string& f : failures) message += "\n  " + f;
  throw Error(message);
}

std::unique_ptr<GlContext> GlContext::AdoptCurrent() {
  std::unique_ptr<GlContext> gl(new GlContext());
  gl->owned_ = false;
  gl->device_.renderer = GlString(GL_RENDERER);
  if (gl->device_.renderer.empty()) throw Error("no OpenGL context is current on this thread");
  gl->device_.vendor = GlString(GL_VENDOR);
  gl->device_.version = GlString(GL_VERSION);
  gl->device_.software = IsSoftwareRenderer(gl->device_.renderer);
  if (epoxy_gl_version() < 43)
    throw Error("the window's OpenGL " + gl->device_.version + " is older than 4.3");
  return gl;
}

GlContext::~GlContext() {
  if (!owned_ || display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  // The display stays initialised: EGL shares it between every context made on it.
}

void GlContext::MakeCurrent() const {
  if (!owned_) return;
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    throw Error("the OpenGL context could not be made current (" + EglErrorName(eglGetError()) +
                ")");
}

}  // namespace lfcam
