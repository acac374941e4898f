# Embeds the GLSL sources of shaders/ into a C++ file at build time:
#   cmake -DOUT=file.cpp -DSOURCES="a.vert|a.frag" -P embed.cmake
set(text "// Generated from shaders/ by shaders/embed.cmake; do not edit.\n#include \"render/shaders.h\"\nnamespace render {\n")
string(REPLACE "|" ";" SOURCES "${SOURCES}")
foreach(src ${SOURCES})
  get_filename_component(name ${src} NAME)
  string(REPLACE "." "_" id ${name})
  file(READ ${src} body)
  string(APPEND text "const char* const shader_${id} = R\"GLSL(${body})GLSL\";\n")
endforeach()
string(APPEND text "}  // namespace render\n")
file(WRITE ${OUT}.tmp "${text}")
file(RENAME ${OUT}.tmp ${OUT})
