#version 330 core
in vec2 v_offset_px;
in float v_radius_px;
in vec4 v_fill;
in vec4 v_halo;

uniform float u_outline_px;   // dark rim inside the disk edge
uniform vec4 u_outline;
uniform float u_halo_px;

out vec4 o_color;  // premultiplied alpha

void main() {
  float d = length(v_offset_px) - v_radius_px;  // signed distance to the edge, pixels
  float inside = clamp(0.5 - d, 0.0, 1.0);       // antialiased coverage of the disk
  float rim = clamp(d + u_outline_px + 0.5, 0.0, 1.0);
  vec3 rgb = mix(v_fill.rgb, u_outline.rgb, rim * u_outline.a);
  vec4 disk = vec4(rgb * v_fill.a, v_fill.a) * inside;
  // Halo: a ring just outside the edge, under the disk.
  float ring = clamp(0.5 + d, 0.0, 1.0) * clamp(u_halo_px + 0.5 - d, 0.0, 1.0) * v_halo.a;
  vec4 halo = vec4(v_halo.rgb * ring, ring);
  o_color = disk + halo * (1.0 - disk.a);
  if (o_color.a <= 0.0) discard;
}
