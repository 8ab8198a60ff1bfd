#include "lfcam/viewer/frame_display.h"

#include <epoxy/gl.h>

#include <string>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// A triangle that covers the viewport, its texture coordinates from the vertex index.
constexpr const char* kVertexShader = R"glsl(#version 330 core
uniform bool top_down;
out vec2 uv;
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = vec2(corner.x, top_down ? 1.0 - corner.y : corner.y);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)glsl";

constexpr const char* kFragmentShader = R"glsl(#version 330 core
uniform sampler2D frame;
in vec2 uv;
out vec4 colour;
vec3 EncodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() { colour = vec4(EncodeSrgb(texture(frame, uv).rgb), 1.0); }
)glsl";

GLuint Compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw Error(std::string("OpenGL: the viewer's display shader did not compile: ") + log);
  }
  return shader;
}

}  // namespace

FrameDisplay::FrameDisplay() {
  const GLuint vertex = Compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fragment = Compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) throw Error("OpenGL: the viewer's display shader did not link");
  glGenVertexArrays(1, &vertex_array_);
  glGenTextures(1, &texture_);
}

FrameDisplay::~FrameDisplay() {
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteTextures(1, &texture_);
}

void FrameDisplay::Upload(const cv::Mat& linear_rgb) {
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, int(linear_rgb.step1() / 3));
  if (linear_rgb.cols != texture_width_ || linear_rgb.rows != texture_height_) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, linear_rgb.cols, linear_rgb.rows, 0, GL_RGB, GL_FLOAT,
                 linear_rgb.data);
    texture_width_ = linear_rgb.cols;
    texture_height_ = linear_rgb.rows;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, linear_rgb.cols, linear_rgb.rows, GL_RGB, GL_FLOAT,
                    linear_rgb.data);
  }
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

void FrameDisplay::Draw(unsigned texture, bool top_down, int framebuffer_width,
                        int framebuffer_height) const {
  glViewport(0, 0, framebuffer_width, framebuffer_height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "top_down"), top_down ? 1 : 0);
  glUniform1i(glGetUniformLocation(program_, "frame"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture);
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace lfcam
