#version 330 core
in vec2 v_px;
flat in vec2 v_a_px;
flat in vec2 v_b_px;
flat in float v_half_px;
in vec4 v_color;
out vec4 o_color;  // premultiplied alpha

void main() {
  vec2 ab = v_b_px - v_a_px;
  float h = dot(ab, ab) > 0.0 ? clamp(dot(v_px - v_a_px, ab) / dot(ab, ab), 0.0, 1.0) : 0.0;
  float d = length(v_px - (v_a_px + h * ab)) - v_half_px;
  float cover = clamp(0.5 - d, 0.0, 1.0) * v_color.a;
  if (cover <= 0.0) discard;
  o_color = vec4(v_color.rgb * cover, cover);
}
