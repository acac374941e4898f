#version 330 core
// Instanced line segments with round caps (walls, arch bonds, scale bar), antialiased by distance.
layout(location = 0) in vec2 a_corner;   // quad corner in [-1, 1]^2
layout(location = 1) in vec4 a_ends;     // a.x, a.y, b.x, b.y (m)
layout(location = 2) in vec4 a_color;    // straight alpha
layout(location = 3) in float a_width_px;

uniform mat3 u_world_to_clip;
uniform float u_px_per_m;

out vec2 v_px;       // this fragment, pixels (world * px_per_m)
flat out vec2 v_a_px;
flat out vec2 v_b_px;
flat out float v_half_px;
out vec4 v_color;

void main() {
  vec2 a = a_ends.xy, b = a_ends.zw;
  vec2 dir = b - a;
  float len = length(dir);
  vec2 t = len > 0.0 ? dir / len : vec2(1.0, 0.0);
  vec2 n = vec2(-t.y, t.x);
  float half_m = (0.5 * a_width_px + 1.5) / u_px_per_m;
  vec2 along = (a_corner.x < 0.0) ? a - t * half_m : b + t * half_m;
  vec2 world = along + n * a_corner.y * half_m;
  gl_Position = vec4((u_world_to_clip * vec3(world, 1.0)).xy, 0.0, 1.0);
  v_px = world * u_px_per_m;
  v_a_px = a * u_px_per_m;
  v_b_px = b * u_px_per_m;
  v_half_px = 0.5 * a_width_px;
  v_color = a_color;
}
