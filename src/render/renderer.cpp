#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "render/gl.h"
#include "render/shaders.h"

namespace render {

namespace {
GLuint compile(GLenum type, const char* src, const char* name) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    throw core::RuntimeFault(std::string("shader ") + name + " does not compile: " + log);
  }
  return s;
}

GLuint link(const char* vs, const char* fs, const char* name) {
  GLuint v = compile(GL_VERTEX_SHADER, vs, name), f = compile(GL_FRAGMENT_SHADER, fs, name);
  GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    glDeleteProgram(p);
    throw core::RuntimeFault(std::string("shader program ") + name + " does not link: " + log);
  }
  return p;
}

// Attribute `loc` of `count` floats at `offset` in instances of `stride` bytes, advancing once per instance.
void instance_attrib(GLuint loc, int count, size_t stride, size_t offset) {
  glEnableVertexAttribArray(loc);
  glVertexAttribPointer(loc, count, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                        reinterpret_cast<void*>(offset));
  glVertexAttribDivisor(loc, 1);
}
}  // namespace

Renderer::Renderer() {
  disk_program_ = link(shader_disk_vert, shader_disk_frag, "disk");
  segment_program_ = link(shader_segment_vert, shader_segment_frag, "segment");
  const float quad[] = {-1, -1, 1, -1, -1, 1, 1, 1};
  glGenBuffers(1, &quad_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, quad_vbo_);
  glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);

  glGenVertexArrays(1, &disk_vao_);
  glGenBuffers(1, &disk_vbo_);
  glBindVertexArray(disk_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, quad_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, disk_vbo_);
  instance_attrib(1, 3, sizeof(ShapeInstance), offsetof(ShapeInstance, x));
  instance_attrib(2, 4, sizeof(ShapeInstance), offsetof(ShapeInstance, fill));
  instance_attrib(3, 4, sizeof(ShapeInstance), offsetof(ShapeInstance, halo));
  instance_attrib(4, 4, sizeof(ShapeInstance), offsetof(ShapeInstance, shape));

  glGenVertexArrays(1, &segment_vao_);
  glGenBuffers(1, &segment_vbo_);
  glBindVertexArray(segment_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, quad_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, segment_vbo_);
  instance_attrib(1, 4, sizeof(SegmentInstance), offsetof(SegmentInstance, ax));
  instance_attrib(2, 4, sizeof(SegmentInstance), offsetof(SegmentInstance, color));
  instance_attrib(3, 1, sizeof(SegmentInstance), offsetof(SegmentInstance, width_px));
  glBindVertexArray(0);
  check_gl("Renderer setup");
}

Renderer::~Renderer() {
  glDeleteBuffers(1, &quad_vbo_);
  glDeleteBuffers(1, &disk_vbo_);
  glDeleteBuffers(1, &segment_vbo_);
  glDeleteVertexArrays(1, &disk_vao_);
  glDeleteVertexArrays(1, &segment_vao_);
  glDeleteProgram(disk_program_);
  glDeleteProgram(segment_program_);
}

void Renderer::draw(const core::Frame& frame, const core::Geometry& geo, const std::vector<View>& views,
                    const Style& style, int w, int h, const ArchStyle& arch) {
  paint(build_draw_list(frame, geo, style, arch), views, style, w, h);
}

void Renderer::paint(const DrawList& list, const std::vector<View>& views, const Style& style, int w, int h) {
  disks_ = list.shapes;
  walls_ = list.walls;
  bonds_ = list.bonds;
  chains_ = list.chains;
  trails_ = list.trails;
  trail_width_m_ = list.trail_width_m;
  chain_width_m_ = list.chain_width_m;
  halo_m_ = list.halo_m;
  halo_edge_ = list.halo_edge;
  bond_m_ = list.bond_m;
  wall_m_ = list.wall_m;
  // Draws into whatever framebuffer the caller bound (an off-screen Target, or a window's).
  glViewport(0, 0, w, h);
  glDisable(GL_SCISSOR_TEST);
  const Rgba bg = background_color(style);
  glClearColor(bg.r * bg.a, bg.g * bg.a, bg.b * bg.a, bg.a);
  if (style.clear) glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied alpha
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glBindBuffer(GL_ARRAY_BUFFER, disk_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(disks_.size() * sizeof(ShapeInstance)), disks_.data(),
               GL_STREAM_DRAW);
  for (const auto& v : views) draw_view(v, h);
  glDisable(GL_SCISSOR_TEST);
  check_gl("Renderer::draw");
}

void Renderer::draw_view(const View& v, int image_h) {
  // GL viewports count from the bottom-left corner.
  glViewport(v.rect.x, image_h - v.rect.y - v.rect.h, v.rect.w, v.rect.h);
  glEnable(GL_SCISSOR_TEST);
  glScissor(v.rect.x, image_h - v.rect.y - v.rect.h, v.rect.w, v.rect.h);
  const auto m = v.world_to_clip();
  const float s = static_cast<float>(v.px_per_m());
  const float scale = std::max(1.0f, image_h / 1080.0f);

  // Walls and bonds: widths from metres, at least 2 px so they stay visible in the whole-hopper view.
  auto draw_segments = [&](std::vector<SegmentInstance>& segs, float width_m,
                           const std::vector<float>* widths = nullptr) {
    if (segs.empty()) return;
    for (size_t k = 0; k < segs.size(); ++k)
      segs[k].width_px = std::max((widths ? 1.5f : 2.0f) * scale, (widths ? (*widths)[k] : width_m) * s);
    glUseProgram(segment_program_);
    glUniformMatrix3fv(glGetUniformLocation(segment_program_, "u_world_to_clip"), 1, GL_FALSE, m.data());
    glUniform1f(glGetUniformLocation(segment_program_, "u_px_per_m"), s);
    glBindVertexArray(segment_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, segment_vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(segs.size() * sizeof(SegmentInstance)), segs.data(),
                 GL_STREAM_DRAW);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(segs.size()));
  };
  draw_segments(walls_, wall_m_);

  glUseProgram(disk_program_);
  glUniformMatrix3fv(glGetUniformLocation(disk_program_, "u_world_to_clip"), 1, GL_FALSE, m.data());
  glUniform1f(glGetUniformLocation(disk_program_, "u_px_per_m"), s);
  const float halo_px = std::max(2.0f * scale, halo_m_ * s);
  glUniform1f(glGetUniformLocation(disk_program_, "u_halo_px"), halo_px);
  glUniform1f(glGetUniformLocation(disk_program_, "u_halo_edge_px"),
              halo_edge_.a > 0 ? std::max(1.0f * scale, 0.35f * halo_px) : 0.0f);
  glUniform4f(glGetUniformLocation(disk_program_, "u_halo_edge"), halo_edge_.r, halo_edge_.g, halo_edge_.b,
              halo_edge_.a);
  glUniform1f(glGetUniformLocation(disk_program_, "u_outline_px"), std::max(0.75f, 0.0025f * s));
  glUniform4f(glGetUniformLocation(disk_program_, "u_outline"), 0.1f, 0.1f, 0.1f, 0.55f);
  glBindVertexArray(disk_vao_);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(disks_.size()));

  draw_segments(trails_, 0, &trail_width_m_);  // over the grains: in a packing they would hide it
  draw_segments(chains_, 0, &chain_width_m_);
  draw_segments(bonds_, bond_m_);
  glBindVertexArray(0);
}

}  // namespace render
