#pragma once
// What every GL compute pass of lfcam shares (the renderer, render/gl_renderer.h; the depth
// sweep, depth/gl_cost_volume.h): compiling a compute shader and checking GL's error state.
// Call with a GL 4.3 context current (gpu/gl_context.h).
#include <epoxy/gl.h>

#include <string>

namespace lfcam {

// Throws lfcam::Error when GL reports an error; `what` says what was being done.
void CheckGl(const std::string& what);

// A compute program from GLSL `shader_text`, compiled as "#version 430 core" after `defines`
// (lines of "#define NAME VALUE"). Throws lfcam::Error with the compiler's log when it does not
// compile or link.
GLuint CompileProgram(const char* shader_text, const std::string& defines);

}  // namespace lfcam
