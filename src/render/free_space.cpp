#include "render/free_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/overlay.h"

namespace render {

namespace {
// The container as the boxes must keep off it, in the container's own frame (m): inside the walls, a grain
// diameter above its top (grains poured in), and the column below the aperture that exiting grains fall
// through (four diameters deep); `m` widens it by the walls' drawn half-thickness and a safety.
bool in_container(const core::Geometry& g, core::Vec2 p, double m) {
  const double d = g.grain_diameter;
  if (p.y < -4 * d) return false;
  if (p.y < m) {  // the outlet's level and below
    if (std::abs(p.x) < g.half_aperture + m) return true;
    // A flat silo's floor with its thickness (a hopper's walls meet the outlet's edges).
    return g.kind == core::ContainerKind::Flat && p.y > -m && p.x > g.x_left - m && p.x < g.x_right + m;
  }
  if (p.y > g.total_height + d + m) return false;
  return p.x > g.left_at(p.y) - m && p.x < g.right_at(p.y) + m;
}
}  // namespace

FreeSpace::FreeSpace(Box region, float cell) : region_(region), cell_(std::max(1.0f, cell)) {
  nx_ = std::max(1, static_cast<int>(std::ceil(region_.w() / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(region_.h() / cell_)));
  blocked_.assign(static_cast<size_t>(nx_) * ny_, 0);
}

void FreeSpace::mark_cell(int i, int j) {
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return;
  blocked_[static_cast<size_t>(j) * nx_ + i] = 1;
  dirty_ = true;
}

void FreeSpace::block_container(const std::vector<View>& views, const core::Geometry& geo, double dx,
                                double dy) {
  // Each cell is tested at its corners and centre (a wall thinner than a cell is still found: the margin
  // is at least a cell wide in metres).
  for (const auto& v : views) {
    const double px_m = v.px_per_m();
    if (!(px_m > 0)) continue;
    // The walls' drawn half-thickness (0.012 m, at least a pixel), two pixels of anti-aliasing and a cell.
    const double m = (0.5 * 0.012 * px_m + 2.0 + cell_) / px_m;
    const int i0 = std::max(0, static_cast<int>((v.rect.x - region_.x0) / cell_));
    const int i1 = std::min(nx_, static_cast<int>(std::ceil((v.rect.x + v.rect.w - region_.x0) / cell_)));
    const int j0 = std::max(0, static_cast<int>((v.rect.y - region_.y0) / cell_));
    const int j1 = std::min(ny_, static_cast<int>(std::ceil((v.rect.y + v.rect.h - region_.y0) / cell_)));
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        bool hit = false;
        for (int s = 0; s < 5 && !hit; ++s) {
          const float fx = s == 4 ? 0.5f : static_cast<float>(s % 2),
                      fy = s == 4 ? 0.5f : static_cast<float>(s / 2);
          const float px = std::clamp(region_.x0 + (i + fx) * cell_, static_cast<float>(v.rect.x),
                                      static_cast<float>(v.rect.x + v.rect.w));
          const float py = std::clamp(region_.y0 + (j + fy) * cell_, static_cast<float>(v.rect.y),
                                      static_cast<float>(v.rect.y + v.rect.h));
          const core::Vec2 w = v.pixel_to_world({px, py});
          hit = in_container(geo, {w.x - dx, w.y - dy}, m);
        }
        if (hit) mark_cell(i, j);
      }
  }
}

void FreeSpace::block_grains(const core::Frame& f, const std::vector<View>& views) {
  for (const auto& v : views) {
    const double s = v.px_per_m();
    for (const auto& p : f.particles) {
      const core::Vec2 c = v.world_to_pixel({p.x, p.y});
      const double r = 1.3 * p.radius * s + 2;  // with the arch's ring and anti-aliasing
      if (c.x + r < v.rect.x || c.x - r > v.rect.x + v.rect.w || c.y + r < v.rect.y ||
          c.y - r > v.rect.y + v.rect.h)
        continue;
      Box b{static_cast<float>(std::max<double>(c.x - r, v.rect.x)),
            static_cast<float>(std::max<double>(c.y - r, v.rect.y)),
            static_cast<float>(std::min<double>(c.x + r, v.rect.x + v.rect.w)),
            static_cast<float>(std::min<double>(c.y + r, v.rect.y + v.rect.h))};
      mark_box(b, 0);
    }
  }
}

FreeSpace::Cells FreeSpace::cells_of(const Box& b, float pad) const {
  return {static_cast<int>(std::floor((b.x0 - pad - region_.x0) / cell_)),
          static_cast<int>(std::ceil((b.x1 + pad - region_.x0) / cell_)),
          static_cast<int>(std::floor((b.y0 - pad - region_.y0) / cell_)),
          static_cast<int>(std::ceil((b.y1 + pad - region_.y0) / cell_))};
}

void FreeSpace::mark_box(const Box& b, float pad) {
  const Cells c = cells_of(b, pad);
  for (int j = std::max(0, c.j0); j < std::min(ny_, c.j1); ++j)
    for (int i = std::max(0, c.i0); i < std::min(nx_, c.i1); ++i) mark_cell(i, j);
}

void FreeSpace::block(const Box& b, float pad) {
  // Kept as a rectangle: the few boxes a picture places are tested against directly, so placing one does
  // not rebuild the summed-area table of the container and the grains (issue 59: a rebuild for every box of
  // every picture cost more than drawing it).
  placed_.push_back(cells_of(b, pad));
}

void FreeSpace::update() const {
  if (!dirty_) return;
  sum_.assign(static_cast<size_t>(nx_ + 1) * (ny_ + 1), 0);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      sum_[static_cast<size_t>(j + 1) * (nx_ + 1) + i + 1] =
          blocked_[static_cast<size_t>(j) * nx_ + i] + sum_[static_cast<size_t>(j) * (nx_ + 1) + i + 1] +
          sum_[static_cast<size_t>(j + 1) * (nx_ + 1) + i] - sum_[static_cast<size_t>(j) * (nx_ + 1) + i];
  dirty_ = false;
}

long FreeSpace::covered(const Box& b) const {
  update();
  // Cells the box touches (a box edge on a cell boundary does not touch the next cell).
  const int i0 = static_cast<int>(std::floor((b.x0 - region_.x0) / cell_ + 1e-4f));
  const int i1 = static_cast<int>(std::ceil((b.x1 - region_.x0) / cell_ - 1e-4f));
  const int j0 = static_cast<int>(std::floor((b.y0 - region_.y0) / cell_ + 1e-4f));
  const int j1 = static_cast<int>(std::ceil((b.y1 - region_.y0) / cell_ - 1e-4f));
  long outside = 0;
  const int ci0 = std::clamp(i0, 0, nx_), ci1 = std::clamp(i1, 0, nx_);
  const int cj0 = std::clamp(j0, 0, ny_), cj1 = std::clamp(j1, 0, ny_);
  const long all = static_cast<long>(std::max(0, i1 - i0)) * std::max(0, j1 - j0);
  const long in = static_cast<long>(ci1 - ci0) * (cj1 - cj0);
  outside = all - in;
  auto S = [&](int i, int j) { return sum_[static_cast<size_t>(j) * (nx_ + 1) + i]; };
  long blocked = in > 0 ? S(ci1, cj1) - S(ci0, cj1) - S(ci1, cj0) + S(ci0, cj0) : 0;
  // The boxes placed: the cells the box shares with each, inside the region.
  for (const Cells& p : placed_) {
    const int a0 = std::max({ci0, p.i0, 0}), a1 = std::min({ci1, p.i1, nx_});
    const int b0 = std::max({cj0, p.j0, 0}), b1 = std::min({cj1, p.j1, ny_});
    if (a1 > a0 && b1 > b0) blocked += static_cast<long>(a1 - a0) * (b1 - b0);
  }
  return blocked + outside;
}

std::optional<Box> FreeSpace::place(float w, float h, const Box& within, float tx, float ty, float ax,
                                    float ay) const {
  if (!(w > 0 && h > 0)) return std::nullopt;
  const Box lim{std::max(within.x0, region_.x0), std::max(within.y0, region_.y0),
                std::min(within.x1, region_.x1), std::min(within.y1, region_.y1)};
  if (lim.w() < w || lim.h() < h) return std::nullopt;
  // Candidate top-left corners on the cell grid, plus the limits' own edges (a box flush with the panel).
  std::vector<float> xs, ys;
  for (float x = lim.x0; x <= lim.x1 - w + 1e-3f; x += cell_) xs.push_back(x);
  xs.push_back(lim.x1 - w);
  for (float y = lim.y0; y <= lim.y1 - h + 1e-3f; y += cell_) ys.push_back(y);
  ys.push_back(lim.y1 - h);
  std::optional<Box> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (float y : ys)
    for (float x : xs) {
      const double ddx = x + ax * w - tx, ddy = y + ay * h - ty;
      const double d = ddx * ddx + ddy * ddy;
      if (d >= best_d) continue;
      const Box b{x, y, x + w, y + h};
      if (covered(b) == 0) best = b, best_d = d;
    }
  return best;
}

std::optional<Box> FreeSpace::place_at_corner(float w, float h, const Box& within, int k, float pad) const {
  const Box in{within.x0 + pad, within.y0 + pad, within.x1 - pad, within.y1 - pad};
  const float ax = k % 2 == 0 ? 1.0f : 0.0f, ay = k < 2 ? 0.0f : 1.0f;
  return place(w, h, in, ax > 0 ? in.x1 : in.x0, ay > 0 ? in.y1 : in.y0, ax, ay);
}

float overlay_style_scale(float em) {
  // Square root: at 4K (51 px) a gap of 16 px, not 31: the words stay apart and the box keeps its size.
  return std::max(1.0f, std::sqrt(em / 13.0f));
}

float info_title_wrap(float em, int margin_w) {
  float wrap = 18 * em;
  if (margin_w > 0) wrap = std::min(wrap, margin_w - 1.2f * em - 2 * 8.0f);  // ImGui's window padding: 8 px
  return std::max(8 * em, wrap);
}

int heading_height(const std::string& text, float em, int panel_w) {
  if (text.empty()) return 0;
  const float hem = kHeadingScale * em, wrap = std::max(4.0f * em, panel_w - 2.0f * em);
  // Characters average under half an em (0.46 measured on the overlay's font); words do not fill their rows:
  // 15% more. At most three rows.
  const int rows = std::clamp(static_cast<int>(std::ceil(1.15f * text.size() * 0.5f * hem / wrap)), 1, 3);
  return static_cast<int>(std::ceil(rows * 1.2f * hem + 0.3f * em));
}

float heading_width(const std::string& text, float em, int panel_w) {
  return std::min(0.5f * kHeadingScale * em * static_cast<float>(text.size()), panel_w - 2.0f * em);
}

float overlay_em(int h, double font_scale) {
  return static_cast<float>(
      std::max(13, static_cast<int>(std::lround(h / 42.0 * std::clamp(font_scale, 0.25, 8.0)))));
}

std::pair<float, float> info_box_estimate(const OverlayOptions& o, float em,
                                          const std::vector<std::string>& species, const std::string& title,
                                          bool colour_rows, float wrap) {
  // ImGui's default style: 8 px window padding, 4 px between rows, a progress bar 6 px taller than text (the
  // gaps within a row scale with the text: overlay_style_scale). Characters of the sans-serif font average
  // under half an em (measured: 0.46 em on the rate line); the title wraps at `wrap` (words do not fill rows:
  // 15% more than its length).
  const float ch = 0.5f * em;
  float w = 0, h = 16;
  int items = 0;
  auto line = [&](size_t chars, float extra_h = 0) {
    w = std::max(w, chars * ch);
    h += em + extra_h;
    ++items;
  };
  size_t names = 0, first = species.empty() ? 8 : species.front().size();
  for (const auto& n : species) names += n.size() + 6;  // "1234 name "
  if (!title.empty()) {
    const float tw = title.size() * ch;
    const int rows = static_cast<int>(std::ceil(1.15f * tw / wrap));
    w = std::max(w, std::min(tw, wrap));
    h += rows * em;
    ++items;
  }
  if (o.time) line(12);
  // "40 original 12 added exits", or from three species on "52 exits: 30 a 12 b 10 c" (up to three digits
  // and a space before each name).
  size_t letters = 0;
  for (const auto& n : species) letters += n.size();
  if (o.counts) line(species.size() > 2 ? letters + 4 * species.size() + 11 : names + 8);
  if (o.rate) line(24 + first);                                // "Q~ = 12.34 /s (originals, so far)"
  if (o.timer) line(0, 6), w = std::max(w, 5 * em + 21 * ch);  // the bar, then "clogged 12.3 s / 5 s"
  if (o.arch) line(24);
  if (o.legend) {
    h += 1;
    ++items;  // the separator
    // The species' swatches and the arch's, on one row: each name and a swatch of about 2.5 em (measured:
    // 18.6 em for three species and the arch at 2x, where this gives 20 em).
    line(letters + 4 + 5 * (species.size() + 1));
    if (colour_rows) line(20, 0), w = std::max(w, 8 * em + 20 * ch), line(20, 0);
  }
  h += 4.0f * std::max(0, items - 1);
  return {w + 16, 1.02f * h};
}

std::pair<float, float> plot_box_size(float view_w, float view_h, float em, float max_w, float height) {
  // The plot's axes 0.42 x 0.2 of the view, with room for the count left of it, the caption below (at
  // least its width) and a little above and right.
  const float caption = 0.5f * em * 34;
  float pw = std::max(0.42f * view_w, caption);
  pw = std::min(pw, max_w - 3.0f * em);
  const float ph = std::max(3.0f * em, height * view_h);
  return {pw + 3.0f * em, ph + 2.9f * em};
}

std::vector<std::pair<float, float>> plot_box_sizes(float view_w, float view_h, float em, float margin_w,
                                                    float beside) {
  std::vector<std::pair<float, float>> out = {plot_box_size(view_w, view_h, em)};
  const float pad = 0.6f * em;
  // Beside the information box: a pad from the panel's edge, the box's own pad from the other edge and its
  // blocked surround (0.4 em) and the cell the free space rounds to.
  for (float limit : {margin_w - 2 * pad, beside - 4 * pad, 0.3f * view_w})
    if (limit > 10 * em)
      for (float height : {0.2f, 0.12f}) out.push_back(plot_box_size(view_w, view_h, em, limit, height));
  return out;
}

Box info_band(const Box& panel, float band, float box_h, float pad) {
  return {panel.x0, std::max(panel.y0, panel.y1 - std::max(band, box_h + 2 * pad)), panel.x1, panel.y1};
}

int overlay_margin(const std::function<std::vector<std::vector<View>>(int width)>& views_of,
                   const core::Geometry& geo, const OverlayOptions& o, int panel_x, int panel_w, int h,
                   const std::vector<std::string>& species, const std::string& title, bool colour_rows,
                   int top, int band, const std::vector<std::pair<float, float>>& texts, bool* column_fits,
                   float heading_w) {
  const float em = overlay_em(h, o.font_scale), pad = 0.6f * em;
  const bool info = o.time || o.counts || o.rate || o.timer || o.arch || o.legend;
  // The title wraps at 18 em, or inside a margin (info_contents).
  auto estimate = [&](int margin) {
    return info_box_estimate(o, em, species, title, colour_rows, info_title_wrap(em, margin));
  };
  // Every set of views must leave the boxes clear space.
  auto fits = [&](int margin) {
    const Box panel{static_cast<float>(panel_x), static_cast<float>(top),
                    static_cast<float>(panel_x + panel_w), static_cast<float>(h)};
    const auto [iw, ih] = estimate(margin);
    // The texts may also use the heading's band beside the heading (centred, heading_w wide).
    const Box whole{panel.x0, 0, panel.x1, panel.y1};
    for (const auto& views : views_of(panel_w - margin)) {
      FreeSpace fs(whole, std::max(2.0f, 0.25f * em));
      if (top > 0) {
        const float c = 0.5f * (whole.x0 + whole.x1),
                    half = heading_w > 0 ? 0.5f * heading_w : 0.5f * panel_w;
        fs.block({c - half, 0, c + half, static_cast<float>(top)}, 0.4f * em);
      }
      fs.block_container(views, geo);
      if (info && o.info_at < 0) {
        std::optional<Box> b;
        if (band > 0)
          b = fs.place_at_corner(iw, ih, info_band(panel, static_cast<float>(band), ih, pad), 0, pad);
        if (!b) b = fs.place_at_corner(iw, ih, panel, 0, pad);
        if (!b) return false;
        fs.block(*b, 0.4f * em);
      }
      const View* zoom = &views.front();
      for (const auto& v : views)
        if (v.px_per_m() > zoom->px_per_m()) zoom = &v;
      if (o.plot && o.plot_at < 0) {
        bool placed = false;
        for (const auto& [pw, ph] :
             plot_box_sizes(static_cast<float>(zoom->rect.w), static_cast<float>(zoom->rect.h), em,
                            static_cast<float>(margin), band > 0 ? panel_w - iw : 0.0f)) {
          if (const auto b = fs.place_at_corner(pw, ph, panel, 2, pad)) {
            fs.block(*b, 0.4f * em);
            placed = true;
            break;
          }
        }
        if (!placed) return false;
      }
      if (o.colorbar && !o.legend && colour_rows && o.colorbar_at < 0) {
        const auto b = fs.place_at_corner(8 * em + 24 * 0.5f * em, 2 * em + 24, panel, 0, pad);
        if (!b) return false;
        fs.block(*b, 0.4f * em);
      }
      if (o.scale && o.scale_at < 0) {
        const float sw = std::max(static_cast<float>(geo.grain_diameter * zoom->px_per_m()), 7 * em);
        const Box view{static_cast<float>(zoom->rect.x), static_cast<float>(zoom->rect.y),
                       static_cast<float>(zoom->rect.x + zoom->rect.w),
                       static_cast<float>(zoom->rect.y + zoom->rect.h)};
        auto b = fs.place_at_corner(sw, 1.7f * em, view, 3, em);
        // Outside its view the bar says which view it measures: "1 d = 13 cm (outlet view)".
        if (!b) b = fs.place_at_corner(std::max(sw, 13.0f * em), 1.7f * em, panel, 3, em);
        if (!b) return false;
        fs.block(*b, 0.4f * em);
      }
      // The texts after the boxes (Overlay::place_text): each anywhere clear in the panel.
      for (const auto& [tw, th] : texts) {
        const auto b = fs.place(tw, th, whole, whole.x0, whole.y0, 0.0f, 0.0f);
        if (!b) return false;
        fs.block(*b, 0.25f * em);
      }
    }
    return true;
  };
  if (column_fits) *column_fits = true;
  if (!(info || o.plot || o.scale || o.colorbar || !texts.empty()) || fits(0)) return 0;
  // A column as wide as the information box (the plot wraps into it) and the widest text, at most half the
  // panel; with a band (the caller asks only whether the band alone is room enough), not looked at further.
  float widest = info ? estimate(0).first : 0.0f;
  for (const auto& t : texts) widest = std::max(widest, t.first);
  const int first = std::min(static_cast<int>(std::ceil(widest + 2 * pad)), panel_w / 2);
  if (band > 0) return first;
  // Wider, in steps of an em, while the texts find no room in it.
  for (int m = first; m <= panel_w / 2; m += static_cast<int>(std::ceil(em))) {
    if (fits(m)) return m;
    if (texts.empty()) break;
  }
  if (column_fits) *column_fits = false;
  return first;
}

std::pair<float, float> text_box_estimate(const std::string& text, float em) {
  // Measured on the overlay's font: 13.6 em for "arch removed (5 s rule): 3 disks" (0.43 em a character) and
  // for "a grain in the middle of the pile", 8.5 em for "slow motion 4.12x" (its digits are wider).
  const auto digits = std::count_if(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  const float chars = 0.44f * static_cast<float>(text.size()) + 0.16f * static_cast<float>(digits);
  return {chars * em + 0.8f * em, 1.4f * em};
}

}  // namespace render
