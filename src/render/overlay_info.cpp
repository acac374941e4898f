// The overlay's information box: its lines (also shown in the windows' side panels) and where it goes on a
// picture, off the container and the arch where a corner allows; the lone colour bar.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/overlay.h"
#include "render/overlay_detail.h"

namespace render {

using overlay_detail::colour_bar;
using overlay_detail::most_zoomed;
using overlay_detail::to_u32;

namespace {
// A world point on the container as the information box must not cover it: inside the walls (and a tenth of
// a diameter beyond, for the walls' lines) or in the column below the aperture that exiting disks fall
// through (four diameters deep).
bool in_container(const core::Geometry& g, core::Vec2 p) {
  const double m = 0.1 * g.grain_diameter;
  if (p.y < 0) return p.y > -4 * g.grain_diameter && std::abs(p.x) < g.half_aperture + m;
  if (p.y > g.total_height + m) return false;
  return p.x > g.left_at(p.y) - m && p.x < g.right_at(p.y) + m;
}
}  // namespace

// The information box's lines, into the current ImGui window.
void info_contents(const core::Frame& f, const OverlayData& d, const OverlayOptions& o, const Style& given,
                   float em) {
  Style style = given;  // the scene's own species colours, wherever the box is drawn (a window's side panel)
  if (!d.species_colors.empty()) style.species_colors = d.species_colors;
  if (!d.title.empty()) ImGui::TextUnformatted(d.title.c_str());
  if (o.time) ImGui::Text("t = %.2f s", f.t);
  const bool shorthand = d.species_names.size() == 2 && d.species_names[0] == "original";
  auto colored = [&](core::Species sp, const std::string& text) {
    const Rgba c = species_color(style, sp);
    ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1), "%s", text.c_str());
  };
  if (o.counts) {
    // Each species' exits in its own colour: "40 original 12 added exits", "52 exits: 30 a, 22 b".
    const size_t n_species = std::max<size_t>(1, d.species_names.size());
    if (n_species == 1) {
      ImGui::Text("%lld exits", static_cast<long long>(f.exits_total()));
    } else {
      if (!shorthand) {
        ImGui::Text("%lld exits:", static_cast<long long>(f.exits_total()));
        ImGui::SameLine();
      }
      for (size_t k = 0; k < n_species; ++k) {
        if (k > 0) ImGui::SameLine();
        colored(static_cast<core::Species>(k),
                std::to_string(f.exits_of(static_cast<int>(k))) + " " + d.species_names[k]);
      }
      if (shorthand) {
        ImGui::SameLine();
        ImGui::TextUnformatted("exits");
      }
    }
  }
  if (o.rate)
    ImGui::Text("%s = %.2f /s (%s, so far)", shorthand || d.species_names.size() > 1 ? "Q~" : "Q",
                f.t > 0 ? static_cast<double>(f.exits_of(0)) / f.t : 0.0,
                shorthand ? "originals" : d.species_names.front().c_str());
  if (o.timer) {
    const bool clogged = f.clog_open;  // as the simulation's step reported it
    const double frac = d.clog_rule ? std::min(1.0, f.since_last_exit / d.clog_timeout) : clogged ? 1.0 : 0.0;
    ImGui::PushStyleColor(ImGuiCol_PlotHistogram,
                          clogged ? ImVec4(0.85f, 0.25f, 0.15f, 1) : ImVec4(0.3f, 0.6f, 0.3f, 1));
    char label[64];
    if (!clogged)
      std::snprintf(label, sizeof label, "flowing");
    else if (d.clog_rule)
      std::snprintf(label, sizeof label, "clogged %.1f s / %.0f s", f.since_last_exit, d.clog_timeout);
    else
      std::snprintf(label, sizeof label, "clogged %.1f s (no rule)", f.since_last_exit);
    ImGui::ProgressBar(static_cast<float>(frac), ImVec2(14 * em, 0), label);
    ImGui::PopStyleColor();
  }
  if (o.arch && !f.arch.empty()) {
    int added = 0;
    for (int id : f.arch) added += f.particles[id].species != core::Species::Original;
    if (shorthand)
      ImGui::Text("arch: %zu disks (%d added)", f.arch.size(), added);
    else
      ImGui::Text("arch: %zu grains", f.arch.size());
  }
  if (o.legend) {
    ImGui::Separator();
    const float r = 0.4f * em;
    auto swatch = [&](Rgba fill, Rgba ring, const char* text) {
      ImVec2 p = ImGui::GetCursorScreenPos();
      ImVec2 c(p.x + r + 2, p.y + 0.5f * ImGui::GetTextLineHeight());
      if (ring.a > 0) ImGui::GetWindowDrawList()->AddCircle(c, r + 0.15f * em, to_u32(ring), 0, 0.25f * em);
      ImGui::GetWindowDrawList()->AddCircleFilled(c, r, to_u32(fill));
      ImGui::Dummy(ImVec2(2 * r + 0.5f * em, ImGui::GetTextLineHeight()));
      ImGui::SameLine();
      ImGui::TextUnformatted(text);
    };
    if (style.color == ColorMode::Species) {
      for (size_t k = 0; k < d.species_names.size(); ++k) {
        swatch(species_color(style, static_cast<core::Species>(k)), {0, 0, 0, 0}, d.species_names[k].c_str());
        ImGui::SameLine();
      }
      if (style.chains) ImGui::NewLine();
    }
    if (style.color == ColorMode::Id) ImGui::TextUnformatted("colour: grain id");
    colour_bar(style, em);
    swatch({0.85f, 0.85f, 0.85f, 1}, arch_color(style.palette), "arch");
  }
}

void Overlay::draw_colorbar(const OverlayOptions& o, const std::vector<View>& views, const Style& style,
                            float em) {
  bar_rect_ = {};
  if (o.colorbar && !o.legend && (!color_scale_label(style).empty() || style.chains)) {
    const View& zoom = most_zoomed(views);
    // Top-right of the outlet view; with the information box placed by free space, beside it in the same free
    // corner (below a top box, above a bottom one); where it would meet the box, just below it.
    float right = zoom.rect.x + zoom.rect.w - 0.6f * em;
    float top = zoom.rect.y + 0.6f * em;
    const float bw = bar_w_ > 0 ? bar_w_ : 16 * em, bh = bar_h_ > 0 ? bar_h_ : 2 * em;
    ImVec2 pivot(1.0f, 0.0f);
    if (info_shown_ && o.place_clear) {
      const bool left_corner = info_corner_ % 2 == 1, bottom_corner = info_corner_ >= 2;
      right = left_corner ? info_x_ : info_x_ + info_w_;
      pivot.x = left_corner ? 0.0f : 1.0f;
      top = bottom_corner ? info_y_ - 0.4f * em - bh : info_y_ + info_h_ + 0.4f * em;
    } else if (info_shown_ && right - bw < info_x_ + info_w_ && right > info_x_ && top < info_y_ + info_h_ &&
               top + bh > info_y_) {
      top = info_y_ + info_h_ + 0.4f * em;
    }
    ImGui::SetNextWindowPos(ImVec2(right, top), 0, pivot);
    ImGui::SetNextWindowBgAlpha(0.82f);
    ImGui::Begin("colorbar", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    colour_bar(style, em);
    bar_w_ = ImGui::GetWindowSize().x;
    bar_h_ = ImGui::GetWindowSize().y;
    bar_rect_ = {ImGui::GetWindowPos().x, ImGui::GetWindowPos().y, ImGui::GetWindowPos().x + bar_w_,
                 ImGui::GetWindowPos().y + bar_h_};
    ImGui::End();
  }
}

void Overlay::draw_info(const core::Frame& f, const OverlayData& d, const OverlayOptions& o,
                        const std::vector<View>& views, const Style& style, int w, int h,
                        const core::Geometry* geo, float em) {
  // The information panel, top-left of the first view.
  const bool panel = o.time || o.counts || o.rate || o.timer || o.arch || o.legend;
  if (panel) {
    // Top-right corner: the outlet view leaves room there beside the hopper wall; the silo's top stays
    // visible.
    const float right = d.panel_w > 0 ? static_cast<float>(d.panel_x + d.panel_w) : static_cast<float>(w);
    const float left = static_cast<float>(d.panel_x), pad = 0.6f * em;
    // Corner k: its anchor and pivot. In a window, move to the corner covering the fewest disk centres
    // (within a radius); stay where the box is unless another corner is strictly better, so it does not jump.
    float bottom = 0;  // of the lowest view: a window's timeline may lie below
    for (const auto& v : views) bottom = std::max(bottom, static_cast<float>(v.rect.y + v.rect.h));
    if (bottom <= 0) bottom = static_cast<float>(h);
    auto anchor = [&](int k) {
      return ImVec2(k % 2 == 0 ? right - pad : left + pad, k < 2 ? pad : bottom - pad);
    };
    auto pivot = [](int k) { return ImVec2(k % 2 == 0 ? 1.0f : 0.0f, k < 2 ? 0.0f : 1.0f); };
    if (o.info_at >= 0 && o.info_at < 4) {
      info_corner_ = o.info_at;  // the user's corner
    } else if (o.place_clear && info_w_ > 0) {
      // Cost of corner k: the container under the box first (sampled every few pixels), then arch members,
      // then other disks.
      constexpr long kContainer = 1000000;
      auto covered = [&](int k) {
        const ImVec2 a = anchor(k), pv = pivot(k);
        const float x0 = a.x - pv.x * info_w_, y0 = a.y - pv.y * info_h_;
        long n = 0;
        if (geo) {
          const float step = std::max(3.0f, 0.25f * em);
          for (float py = y0; py <= y0 + info_h_; py += step)
            for (float px = x0; px <= x0 + info_w_; px += step)
              for (const auto& v : views)
                if (px >= v.rect.x && px < v.rect.x + v.rect.w && py >= v.rect.y &&
                    py < v.rect.y + v.rect.h && in_container(*geo, v.pixel_to_world({px, py}))) {
                  n += kContainer;
                  break;
                }
        }
        std::vector<char> in_arch(f.particles.size(), 0);
        for (int id : f.arch) in_arch[static_cast<size_t>(id)] = 1;
        for (const auto& v : views) {
          for (size_t i = 0; i < f.particles.size(); ++i) {
            const auto& p = f.particles[i];
            const core::Vec2 c = v.world_to_pixel({p.x, p.y});
            const double r = 1.3 * p.radius * v.px_per_m();  // with the arch's ring
            if (c.x < v.rect.x || c.x > v.rect.x + v.rect.w || c.y < v.rect.y || c.y > v.rect.y + v.rect.h)
              continue;
            // Covering an arch member is worst: it is what the inspector is for.
            if (c.x + r > x0 && c.x - r < x0 + info_w_ && c.y + r > y0 && c.y - r < y0 + info_h_)
              n += in_arch[i] ? 100 : 1;
          }
        }
        return n;
      };
      // The discharge plot (on request) owns the bottom-right of the outlet view: the box keeps out of it.
      long best = covered(info_corner_);
      for (int k = 0; k < 4 && best > 0; ++k) {
        const long n = covered(k);
        if (n < best) best = n, info_corner_ = k;
      }
      info_left_ = o.may_leave && best >= kContainer;
    } else if (!o.place_clear) {
      info_corner_ = 0;
    }
    // Left out of the picture, the box is still laid out (off-screen) so its size follows the options.
    if (info_left_)
      ImGui::SetNextWindowPos(ImVec2(static_cast<float>(w) + 100 * em, 0));
    else
      ImGui::SetNextWindowPos(anchor(info_corner_), 0, pivot(info_corner_));
    ImGui::SetNextWindowBgAlpha(0.82f);
    ImGui::Begin("info", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    info_contents(f, d, o, style, em);
    info_w_ = ImGui::GetWindowSize().x;
    info_h_ = ImGui::GetWindowSize().y;
    info_x_ = ImGui::GetWindowPos().x;
    info_y_ = ImGui::GetWindowPos().y;
    info_shown_ = !info_left_;
    ImGui::End();
  }
}

}  // namespace render
