# Writes a GLSL file as a C++ header holding its text (CMakeLists.txt runs it for each shader).
#   -DINPUT=path/render_frame.comp -DOUTPUT=path/render_frame.comp.h -DNAME=render_frame
# gives `inline constexpr char kRenderFrameShader[]`.
file(READ "${INPUT}" text)
string(FIND "${text}" ")glsl\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} holds the raw string's closing delimiter")
endif()
string(REPLACE "_" ";" parts "${NAME}")
set(symbol "k")
foreach(part IN LISTS parts)
  string(SUBSTRING "${part}" 0 1 first)
  string(SUBSTRING "${part}" 1 -1 rest)
  string(TOUPPER "${first}" first)
  string(APPEND symbol "${first}${rest}")
endforeach()
get_filename_component(source_name "${INPUT}" NAME)
file(WRITE "${OUTPUT}.tmp"
  "#pragma once\n// Generated from ${source_name} by cmake/EmbedShader.cmake: edit the shader, not this.\n"
  "inline constexpr char ${symbol}Shader[] = R\"glsl(${text})glsl\";\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
