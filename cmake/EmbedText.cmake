# Writes a text file (a GLSL shader, the web page's sources) as a C++ header holding it, so that
# the binary carries it (CMakeLists.txt: lfcam_embed_text).
#   -DINPUT=path/lfcam-web.js -DOUTPUT=path/lfcam-web.js.h -DSYMBOL=kLfcamWebJs
file(READ "${INPUT}" text)
string(FIND "${text}" ")lfcamtext\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} holds the raw string's closing delimiter")
endif()
get_filename_component(source_name "${INPUT}" NAME)
file(WRITE "${OUTPUT}.tmp"
  "#pragma once\n// Generated from ${source_name} by cmake/EmbedText.cmake: edit the source, not this.\n"
  "inline constexpr char ${SYMBOL}[] = R\"lfcamtext(${text})lfcamtext\";\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
