#include "lfcam/viewer/glfw_window.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <cctype>
#include <cstdlib>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

std::string glfw_error;  // the last GLFW error, for messages

void OnGlfwError(int code, const char* description) {
  glfw_error = fmt::format("GLFW error 0x{:x}: {}", code, description ? description : "");
}

}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title) {
  glfwSetErrorCallback(OnGlfwError);
  if (!glfwInit())
    throw Error("no window system for the viewer (" + glfw_error +
                "); is DISPLAY set? Without a screen, run it under xvfb-run");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // HiDPI
  handle_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (handle_ == nullptr) {
    const std::string why = glfw_error;
    glfwTerminate();
    throw Error("no window with an OpenGL 4.3 core context (" + why + ")");
  }
  glfwMakeContextCurrent(handle_);
  glfwSwapInterval(1);  // vsync
  glfwSetWindowUserPointer(handle_, this);
  glfwSetScrollCallback(handle_, OnScroll);
  glfwSetKeyCallback(handle_, OnKey);
}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(handle_);
  glfwTerminate();
}

WindowInput GlfwWindow::TakeInput() {
  WindowInput taken;
  std::swap(taken, input_);
  return taken;
}

void GlfwWindow::OnScroll(GLFWwindow* window, double, double dy) {
  static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window))->input_.scroll += dy;
}

void GlfwWindow::OnKey(GLFWwindow* window, int key, int, int action, int) {
  if (action == GLFW_PRESS)
    static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window))->input_.keys_pressed.push_back(key);
}

int GlfwKeyFromName(const std::string& name) {
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_A + (std::toupper(static_cast<unsigned char>(name[0])) - 'A');
  if (name.size() >= 2 && name[0] == 'F') {
    const int n = std::atoi(name.c_str() + 1);
    if (n >= 1 && n <= 25) return GLFW_KEY_F1 + n - 1;
  }
  if (name == "[") return GLFW_KEY_LEFT_BRACKET;
  if (name == "]") return GLFW_KEY_RIGHT_BRACKET;
  if (name == "Esc" || name == "Escape") return GLFW_KEY_ESCAPE;
  if (name == "Space") return GLFW_KEY_SPACE;
  if (name == ",") return GLFW_KEY_COMMA;
  if (name == ".") return GLFW_KEY_PERIOD;
  if (name == "Home") return GLFW_KEY_HOME;
  throw Error("unknown key '" + name + "'");
}

}  // namespace lfcam
