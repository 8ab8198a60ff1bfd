#pragma once
// The viewer's window: GLFW initialised for the window's lifetime, a window with an OpenGL 4.3
// core context (vsync, scaled to the monitor's content scale), and the input its callbacks
// gather between two loops (scroll and key presses; held keys, buttons and the cursor are
// polled).
#include <string>
#include <vector>

struct GLFWwindow;

namespace lfcam {

struct WindowInput {
  double scroll = 0;              // wheel notches
  std::vector<int> keys_pressed;  // GLFW key codes, in order
};

class GlfwWindow {
 public:
  // Throws lfcam::Error naming why when there is no window system or no GL 4.3 context.
  GlfwWindow(int width, int height, const std::string& title);
  ~GlfwWindow();
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  GLFWwindow* handle() const { return handle_; }
  WindowInput TakeInput();  // what the callbacks gathered since the last call

 private:
  static void OnScroll(GLFWwindow* window, double dx, double dy);
  static void OnKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  GLFWwindow* handle_ = nullptr;
  WindowInput input_;
};

// A key as scripts name it ("F1".."F25", a letter, "[", "]", "Esc") to its GLFW code; throws
// lfcam::Error for another name.
int GlfwKeyFromName(const std::string& name);

}  // namespace lfcam
