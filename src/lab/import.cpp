// A lab run from tracked particles (lab/import.h).
#include "lab/import.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/stats.h"
#include "sim/clog.h"

namespace lab {

namespace {

struct Point {
  int frame;
  Detection d;
};
struct Track {
  long id;
  std::vector<Point> points;  // in frame order
  bool joined = false;        // merged into another
  int start() const { return points.front().frame; }
  int end() const { return points.back().frame; }
};

// The track ends where a grain leaves through the outlet: within a diameter above the outlet line, inside the
// opening (or already below it).
bool ends_at_outlet(const Detection& d, const core::Geometry& geo) {
  return d.y < -d.r || (d.y < 2 * d.r && std::fabs(d.x) < geo.half_aperture + 0.5 * d.r);
}

}  // namespace

core::ContactGraph contacts_by_distance(const std::vector<core::Vec2>& pos, const std::vector<double>& radius,
                                        const std::vector<bool>& present, const core::Geometry& geo,
                                        double tolerance) {
  const int n = static_cast<int>(pos.size());
  core::ContactGraph g(n);
  const core::Segment& left = geo.walls[static_cast<int>(core::Wall::HopperLeft)];
  const core::Segment& right = geo.walls[static_cast<int>(core::Wall::HopperRight)];
  // Grains sorted by x: only neighbours within the largest reach are compared.
  std::vector<int> order;
  double rmax = 0;
  for (int i = 0; i < n; ++i)
    if (present[static_cast<size_t>(i)] &&
        pos[static_cast<size_t>(i)].y > -2 * radius[static_cast<size_t>(i)])
      order.push_back(i), rmax = std::max(rmax, radius[static_cast<size_t>(i)]);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return pos[a].x < pos[b].x; });
  const double reach_max = 2 * rmax * (1 + tolerance);
  for (size_t a = 0; a < order.size(); ++a) {
    const int i = order[a];
    const double ri = radius[static_cast<size_t>(i)];
    const double wall_gap = tolerance * 2 * ri;
    g.touches_left[i] = core::distance_to_segment(pos[i], left) <= ri + wall_gap;
    g.touches_right[i] = core::distance_to_segment(pos[i], right) <= ri + wall_gap;
    if (geo.obstacle.present() && geo.obstacle.gap(pos[i]) <= ri + wall_gap) g.on_obstacle.push_back(i);
    for (size_t b = a + 1; b < order.size(); ++b) {
      const int j = order[b];
      if (pos[j].x - pos[i].x > reach_max) break;
      const double rj = radius[static_cast<size_t>(j)];
      const double reach = ri + rj + tolerance * 2 * std::min(ri, rj);
      const core::Vec2 d = pos[i] - pos[j];
      if (core::dot(d, d) <= reach * reach) g.add_bond(i, j);
    }
  }
  return g;
}

std::vector<int> arch_by_distance(const std::vector<core::Vec2>& pos, const std::vector<double>& radius,
                                  const std::vector<bool>& present, const core::Model& model,
                                  double tolerance) {
  const core::Geometry& geo = model.setup.geo;
  std::vector<int> arch =
      core::find_arch(contacts_by_distance(pos, radius, present, geo, tolerance), pos,
                      model.scene.arch_wall_reach, geo.kind == core::ContainerKind::Hopper);
  if (!core::blocks_outlet(arch, pos, radius, geo.half_aperture)) arch.clear();
  return arch;
}

Imported import_tracks(const Tracks& tracks, const core::Model& model, const ImportOptions& opt) {
  const core::Geometry& geo = model.setup.geo;
  const core::Scene& scene = model.scene;
  Imported out;
  ImportReport& rep = out.report;
  const int nf = static_cast<int>(tracks.frames.size());
  rep.frames = nf;
  rep.rows = tracks.rows;
  rep.time_offset = tracks.frames.front().t;
  std::vector<double> t(static_cast<size_t>(nf));
  for (int k = 0; k < nf; ++k) t[k] = tracks.frames[k].t - rep.time_offset;
  {
    std::vector<double> dt;
    for (int k = 1; k < nf; ++k) dt.push_back(t[k] - t[k - 1]);
    rep.interval_median = core::median(dt);
    if (!dt.empty()) {
      rep.interval_min = *std::min_element(dt.begin(), dt.end());
      rep.interval_max = *std::max_element(dt.begin(), dt.end());
    }
    for (double d : dt)
      if (std::fabs(d - rep.interval_median) > 0.01 * rep.interval_median) ++rep.interval_changes;
  }

  // Tracks by the file's ids, then ids that changed joined.
  std::map<long, Track> by_id;
  for (int k = 0; k < nf; ++k)
    for (const Detection& d : tracks.frames[k].found) {
      Track& tr = by_id[d.id];
      tr.id = d.id;
      tr.points.push_back({k, d});
    }
  std::vector<Track> all;
  for (auto& [id, tr] : by_id) all.push_back(std::move(tr));
  rep.tracks = static_cast<long>(all.size());
  std::vector<std::vector<int>> starting(static_cast<size_t>(nf));
  for (int i = 0; i < static_cast<int>(all.size()); ++i)
    starting[static_cast<size_t>(all[i].start())].push_back(i);
  std::vector<int> by_end(all.size());
  for (size_t i = 0; i < all.size(); ++i) by_end[i] = static_cast<int>(i);
  std::sort(by_end.begin(), by_end.end(), [&](int a, int b) { return all[a].end() < all[b].end(); });
  for (int ia : by_end) {
    Track& a = all[static_cast<size_t>(ia)];
    while (!a.joined && a.end() < nf - 1 && !ends_at_outlet(a.points.back().d, geo)) {
      const Detection& last = a.points.back().d;
      int best = -1;
      double best_d = opt.join_distance * 2 * last.r;
      for (int s = a.end() + 1; s <= std::min(nf - 1, a.end() + opt.max_gap + 1); ++s)
        for (int ib : starting[static_cast<size_t>(s)]) {
          const Track& b = all[static_cast<size_t>(ib)];
          if (b.joined || ib == ia || b.points.front().d.species != last.species) continue;
          const double dist = std::hypot(b.points.front().d.x - last.x, b.points.front().d.y - last.y);
          if (dist <= best_d) best_d = dist, best = ib;
        }
      if (best < 0) break;
      Track& b = all[static_cast<size_t>(best)];
      a.points.insert(a.points.end(), b.points.begin(), b.points.end());
      b.joined = true;
      ++rep.joined;
    }
  }
  std::vector<Track> grains;
  for (Track& tr : all)
    if (!tr.joined) grains.push_back(std::move(tr));
  const int n = static_cast<int>(grains.size());
  rep.grains = n;

  // Each grain's size and species, and where it is at every frame.
  out.radius.resize(static_cast<size_t>(n));
  out.species.resize(static_cast<size_t>(n));
  out.track_id.resize(static_cast<size_t>(n));
  double rmax = 0;
  for (int g = 0; g < n; ++g) {
    std::vector<double> r;
    std::vector<int> count(model.setup.species.size(), 0);
    for (const Point& p : grains[g].points) r.push_back(p.d.r), ++count[static_cast<size_t>(p.d.species)];
    out.radius[g] = core::median(r);
    out.species[g] = static_cast<core::Species>(std::max_element(count.begin(), count.end()) - count.begin());
    out.track_id[g] = grains[g].id;
    rmax = std::max(rmax, out.radius[g]);
  }
  std::vector<std::vector<core::Vec2>> pos(static_cast<size_t>(nf),
                                           std::vector<core::Vec2>(static_cast<size_t>(n)));
  std::vector<std::vector<float>> angle(static_cast<size_t>(nf),
                                        std::vector<float>(static_cast<size_t>(n), 0.f));
  std::vector<std::vector<bool>> present(static_cast<size_t>(nf),
                                         std::vector<bool>(static_cast<size_t>(n), false));
  for (int g = 0; g < n; ++g) {
    const auto& pts = grains[g].points;
    for (size_t k = 0; k < pts.size(); ++k) {
      const Point& p = pts[k];
      pos[p.frame][g] = {p.d.x, p.d.y};
      angle[p.frame][g] = static_cast<float>(p.d.angle);
      present[p.frame][g] = true;
      if (k + 1 < pts.size()) {
        const Point& q = pts[k + 1];
        const int missing = q.frame - p.frame - 1;
        if (missing > opt.max_gap) {
          ++rep.long_gaps;
        } else {
          for (int f = p.frame + 1; f < q.frame; ++f) {
            const double w = (t[f] - t[p.frame]) / std::max(1e-12, t[q.frame] - t[p.frame]);
            pos[f][g] = {p.d.x + w * (q.d.x - p.d.x), p.d.y + w * (q.d.y - p.d.y)};
            angle[f][g] = static_cast<float>(p.d.angle + w * (q.d.angle - p.d.angle));
            present[f][g] = true;
            ++rep.interpolated;
          }
        }
      }
    }
    if (grains[g].start() > 0) ++rep.entered;
  }

  // Where a grain is not seen it is parked far below the container, apart from every other (no contact, and
  // never between an arch and the outlet).
  // A grid below the container, as wide as eight times its size (trajectory readers refuse positions farther
  // than ten times the container's size away).
  const double size = std::max(geo.total_height, geo.x_right - geo.x_left), pitch = 2.5 * rmax;
  const long cols = std::max(1L, static_cast<long>((geo.x_right - geo.x_left + 8 * size) / pitch));
  const long rows = static_cast<long>(7 * size / pitch);
  if (n > cols * rows)
    throw core::InputError(tracks.source + ": " + std::to_string(n) +
                           " grains (tracks) where a run holds at most " + std::to_string(cols * rows) +
                           " for this container: join broken tracks (--join-distance, --max-gap) or import a "
                           "shorter stretch");
  auto park = [&](int g) {
    return core::Vec2{geo.x_left - 4 * size + (static_cast<double>(g % cols) + 0.5) * pitch,
                      -(geo.total_height + 1.0) - static_cast<double>(g / cols) * pitch};
  };
  for (int k = 0; k < nf; ++k)
    for (int g = 0; g < n; ++g)
      if (!present[k][g]) pos[k][g] = park(g);

  // Exits: the centre wholly below the outlet line, or a track that ends inside the outlet.
  std::vector<std::vector<int>> exits_at(static_cast<size_t>(nf));
  for (int g = 0; g < n; ++g) {
    int exit_frame = -1;
    for (const Point& p : grains[g].points)
      if (p.d.y < -out.radius[g]) {
        exit_frame = p.frame;
        ++rep.exits_below;
        break;
      }
    const Detection& last = grains[g].points.back().d;
    if (exit_frame < 0 && grains[g].end() < nf - 1) {
      if (ends_at_outlet(last, geo)) {
        exit_frame = grains[g].end() + 1;
        ++rep.exits_lost;
      } else {
        ++rep.left_view;
      }
    }
    if (exit_frame >= 0) exits_at[static_cast<size_t>(exit_frame)].push_back(g);
  }

  // Clogs and arches, frame by frame, by the simulation's rules (no clog rule: nothing removes an arch here).
  const bool driven = model.setup.drive.kick_impulse_max > 0 || model.setup.drive.vibrating();
  sim::ClogTracker tracker(scene.clog_min_gap, 0, driven);
  const double tol = opt.contact_tolerance;
  std::vector<std::int64_t> exits(model.setup.species.size(), 0);
  out.frames.resize(static_cast<size_t>(nf));
  out.between.resize(static_cast<size_t>(nf));
  std::vector<int> held_arch;  // the open clog's arch, and the frame it was last seen at
  int held_frame = -1;
  auto close_arch = [&](const core::StepEvents& ev) {
    for (size_t c = 0; c < ev.clogs_closed.size(); ++c) {
      if (held_arch.empty() || held_frame < 0) continue;
      ClogArch a;
      a.clog = static_cast<int>(tracker.clogs().size() - ev.clogs_closed.size() + c + 1);
      a.t = t[held_frame];
      a.ids = held_arch;
      for (int id : held_arch) a.track_ids.push_back(out.track_id[static_cast<size_t>(id)]);
      a.descriptors = core::arch_descriptors(held_arch, pos[held_frame], out.radius);
      out.clog_arches.push_back(std::move(a));
      held_arch.clear();
      held_frame = -1;
    }
  };
  for (int k = 0; k < nf; ++k) {
    core::StepEvents& ev = out.between[k];
    for (int g : exits_at[k]) {
      ev.exits.push_back({t[k], g, out.species[g]});
      out.events.exits.push_back(ev.exits.back());
      ++exits[static_cast<size_t>(core::species_index(out.species[g]))];
      tracker.on_exit(t[k], ev);
    }
    close_arch(ev);
    std::vector<int> arch = arch_by_distance(pos[k], out.radius, present[k], model, tol);
    if (!arch.empty()) ++rep.frames_with_arch;
    // At rest: the arch and the grains no farther from the outlet's centre held still over arrest_hold.
    bool rest = false;
    if (!arch.empty() && k > 0) {
      int j = k - 1;
      while (j > 0 && t[k] - t[j] < scene.arrest_hold) --j;
      double reach = 0;
      for (int id : arch) reach = std::max(reach, core::length(pos[k][id]) + out.radius[id]);
      rest = true;
      for (int g = 0; g < n && rest; ++g) {
        if (!present[k][g] || core::length(pos[k][g]) > reach) continue;
        if (!present[j][g]) {
          rest = false;
          break;
        }
        const core::Vec2 d = pos[k][g] - pos[j][g];
        const double limit = scene.arrest_shift * out.radius[g];
        if (core::dot(d, d) > limit * limit) rest = false;
      }
    }
    tracker.on_rest_check(t[k], rest, arch);
    tracker.on_step_end(
        t[k], [&] { return arch; }, ev);
    const core::ClogState& st = tracker.state();
    if (st.open) {
      ++rep.frames_clogged;
      rep.frames_clogged_with_arch += !arch.empty();
    } else {
      rep.frames_flowing_with_arch += !arch.empty();
    }
    if (st.open && !st.arch.empty()) {
      held_arch = st.arch;
      held_frame = k;
    }

    core::Frame& f = out.frames[k];
    f.t = t[k];
    f.step = static_cast<std::uint64_t>(k);
    f.particles.resize(static_cast<size_t>(n));
    for (int g = 0; g < n; ++g) {
      core::Particle& p = f.particles[g];
      p.radius = static_cast<float>(out.radius[g]);
      p.species = out.species[g];
      p.force = 0;
      p.vx = p.vy = 0;
      if (!present[k][g]) {
        p.x = static_cast<float>(pos[k][g].x);
        p.y = static_cast<float>(pos[k][g].y);
        p.angle = 0;
        continue;
      }
      p.x = static_cast<float>(pos[k][g].x);
      p.y = static_cast<float>(pos[k][g].y);
      p.angle = angle[k][g];
      const int a = k > 0 && present[k - 1][g] ? k - 1 : k;
      const int b = k + 1 < nf && present[k + 1][g] ? k + 1 : k;
      if (b > a) {
        p.vx = static_cast<float>((pos[b][g].x - pos[a][g].x) / (t[b] - t[a]));
        p.vy = static_cast<float>((pos[b][g].y - pos[a][g].y) / (t[b] - t[a]));
      }
    }
    f.clog_open = st.open;
    f.clog_number = st.number;
    f.clog_start = st.start;
    f.clog_arrested = st.arrested;
    if (st.open) f.arch = st.arch;
    f.rule_due_in = INFINITY;
    f.since_last_exit = tracker.since_last(t[k]);
    f.exits = exits;
  }
  tracker.finish(t[nf - 1], out.after);
  close_arch(out.after);
  out.events.clogs = tracker.clogs();
  return out;
}

}  // namespace lab
