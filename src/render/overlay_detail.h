// Internal to render/overlay*.cpp: the small drawing helpers the overlay's parts share.
#pragma once

#include <imgui.h>

#include <vector>

#include "render/camera.h"
#include "render/palette.h"

namespace render::overlay_detail {

inline ImU32 to_u32(Rgba c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}
// The colour scale of speed or force colouring, inside the current ImGui window.
void colour_bar(const Style& style, float em);
// The view with the most pixels per metre (the outlet panel of a split camera).
const View& most_zoomed(const std::vector<View>& views);
// A text in a light box, centred at (cx, y) on the draw list.
void boxed_text(ImDrawList* dl, float cx, float y, const char* text, ImU32 ink, ImU32 box, float em);

}  // namespace render::overlay_detail
