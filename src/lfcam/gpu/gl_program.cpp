#include "lfcam/gpu/gl_program.h"

#include <fmt/format.h>

#include <algorithm>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

std::string GlErrorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return fmt::format("GL error 0x{:x}", error);
  }
}

}  // namespace

void CheckGl(const std::string& what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw Error(fmt::format("OpenGL: {} failed: {}", what, GlErrorName(error)));
}

GLuint CompileProgram(const char* shader_text, const std::string& defines) {
  const std::string source = "#version 430 core\n" + defines + "#line 1\n" + shader_text;
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  const auto log = [](GLuint object, bool is_program) {
    GLint length = 0;
    if (is_program)
      glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else
      glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string info(std::size_t(std::max(length, 1)), '\0');
    if (is_program)
      glGetProgramInfoLog(object, length, nullptr, info.data());
    else
      glGetShaderInfoLog(object, length, nullptr, info.data());
    return info;
  };
  if (!ok) {
    const std::string message = log(shader, false);
    glDeleteShader(shader);
    throw Error("OpenGL: a compute shader did not compile:\n" + message);
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string message = log(program, true);
    glDeleteProgram(program);
    throw Error("OpenGL: a compute shader did not link:\n" + message);
  }
  return program;
}

}  // namespace lfcam
