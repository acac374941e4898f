// GLSL sources from shaders/, embedded into the binary at build time (see shaders/embed.cmake).
#pragma once

namespace render {
extern const char* const shader_disk_vert;
extern const char* const shader_disk_frag;
extern const char* const shader_segment_vert;
extern const char* const shader_segment_frag;
}  // namespace render
