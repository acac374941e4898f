#version 330 core
in vec2 v_offset_px;
in float v_radius_px;
in vec4 v_fill;
in vec4 v_halo;
flat in vec4 v_shape;

uniform float u_outline_px;   // dark rim inside the grain's edge
uniform vec4 u_outline;
uniform float u_halo_px;
uniform float u_halo_edge_px;  // a dark edge outside the halo (light backgrounds), pixels; 0: none
uniform vec4 u_halo_edge;

out vec4 o_color;  // premultiplied alpha

const float kPi = 3.14159265358979;

// Signed distance to the grain's edge, pixels (negative inside).
float edge_distance() {
  float sides = v_shape.y;
  if (sides < 2.5) return length(v_offset_px) - v_radius_px;
  if (sides > 50.0) {  // a box, half sizes in pixels
    vec2 q = abs(v_offset_px) - v_shape.zw;
    return length(max(q, 0.0)) + min(max(q.x, q.y), 0.0);
  }
  // A regular polygon: the largest distance beyond its edges' lines (exact inside and along the edges; the
  // corners stay sharp). Edge k faces the angle (2k + 1) pi / n from the first vertex.
  float c = cos(v_shape.x), s = sin(v_shape.x);
  vec2 q = vec2(c * v_offset_px.x + s * v_offset_px.y, -s * v_offset_px.x + c * v_offset_px.y);
  int n = int(sides + 0.5);
  float apothem = v_radius_px * cos(kPi / float(n));
  float d = -1e9;
  for (int k = 0; k < 8; ++k) {
    if (k >= n) break;
    float a = (2.0 * float(k) + 1.0) * kPi / float(n);
    d = max(d, dot(q, vec2(cos(a), sin(a))) - apothem);
  }
  return d;
}

void main() {
  float d = edge_distance();
  float inside = clamp(0.5 - d, 0.0, 1.0);       // antialiased coverage of the grain
  float rim = clamp(d + u_outline_px + 0.5, 0.0, 1.0);
  vec3 rgb = mix(v_fill.rgb, u_outline.rgb, rim * u_outline.a);
  vec4 disk = vec4(rgb * v_fill.a, v_fill.a) * inside;
  // Halo: a ring just outside the edge, under the grain, with its edge beyond it.
  float outer = u_halo_px + u_halo_edge_px;
  float ring = clamp(0.5 + d, 0.0, 1.0) * clamp(outer + 0.5 - d, 0.0, 1.0) * v_halo.a;
  float edge = u_halo_edge_px > 0.0 ? clamp(d - u_halo_px + 0.5, 0.0, 1.0) * u_halo_edge.a : 0.0;
  vec4 halo = vec4(mix(v_halo.rgb, u_halo_edge.rgb, edge) * ring, ring);
  o_color = disk + halo * (1.0 - disk.a);
  if (o_color.a <= 0.0) discard;
}
