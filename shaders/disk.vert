#version 330 core
// Instanced grains: one quad per grain, expanded in the vertex shader, coloured by a signed distance field: a
// disk, a regular polygon of 3-8 sides (Box2D's vertices: angle + 2 pi k / n) or an axis-aligned box.
layout(location = 0) in vec2 a_corner;   // quad corner in [-1, 1]^2
layout(location = 1) in vec3 a_disk;     // centre x, y (m), bounding radius (m): the disk's or circumradius
layout(location = 2) in vec4 a_fill;     // fill colour, straight alpha
layout(location = 3) in vec4 a_halo;     // halo colour (alpha 0: no halo)
layout(location = 4) in vec4 a_shape;    // angle (rad), sides (0 disk, 3-8 polygon, 100 box), box half w, h (m)

uniform mat3 u_world_to_clip;
uniform float u_px_per_m;
uniform float u_halo_px;
uniform float u_halo_edge_px;  // the halo's dark edge beyond it (0: none)

out vec2 v_offset_px;   // fragment offset from the centre, pixels, along the world's axes
out float v_radius_px;
out vec4 v_fill;
out vec4 v_halo;
flat out vec4 v_shape;  // angle, sides, box half sizes in pixels

void main() {
  float margin_px = 1.5 + (a_halo.a > 0.0 ? u_halo_px + u_halo_edge_px : 0.0);
  float extent = a_disk.z + margin_px / u_px_per_m;
  vec2 world = a_disk.xy + a_corner * extent;
  gl_Position = vec4((u_world_to_clip * vec3(world, 1.0)).xy, 0.0, 1.0);
  v_offset_px = a_corner * extent * u_px_per_m;
  v_radius_px = a_disk.z * u_px_per_m;
  v_fill = a_fill;
  v_halo = a_halo;
  v_shape = vec4(a_shape.xy, a_shape.zw * u_px_per_m);
}
