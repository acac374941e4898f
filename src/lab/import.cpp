// A lab run from tracked particles (lab/import.h): tracks joined into grains, their paths, exits, then clogs
// and arches by the simulation's own rules, one step of the Importer each. Over 400 lines because the steps
// share one state (every grain's path at every frame) and read best in order; contacts and arches by distance
// are the lab's own geometry, in lab/contacts.cpp.
#include "lab/import.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/clog.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/median.h"
#include "lab/contacts.h"

namespace lab {

namespace {

struct Point {
  int frame;
  int index;  // of the detection in its frame (Importer::d)
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

// The import's steps over one track file, each a method: frame times, tracks joined into grains, each grain's
// size and path, exits, then clogs and arches frame by frame.
class Importer {
 public:
  Importer(Tracks& tracks, const core::Model& model, const ImportOptions& opt)
      : tracks_(tracks), model_(model), geo_(model.setup.geo), opt_(opt), rep_(out_.report) {}

  Imported run() {
    frame_times();
    join_tracks();
    grain_sizes();
    measure_noise();
    find_exits();
    grain_paths();  // the last step that reads the detections: it may release them as it goes
    park_unseen();
    check_calibration();
    release();
    clogs_and_arches();
    out_.paths = {std::move(t_), std::move(pos_), std::move(angle_), std::move(present_)};
    return std::move(out_);
  }

 private:
  Tracks& tracks_;
  const core::Model& model_;
  const core::Geometry& geo_;
  const ImportOptions& opt_;
  Imported out_;
  ImportReport& rep_;
  int nf_ = 0;
  int n_ = 0;   // particles of the run (slots: a grain that left gives its slot to one that comes later)
  int ng_ = 0;  // grains (tracks after joining)
  double rmax_ = 0;
  std::vector<double> t_;
  std::vector<Track> grains_;
  std::vector<double> grain_radius_;
  std::vector<core::Species> grain_species_;
  std::vector<int> slot_of_;                             // per grain
  std::vector<std::vector<std::pair<int, long>>> held_;  // per slot: (first frame, file id) of its grains
  std::vector<std::vector<core::Vec2>> pos_;
  std::vector<std::vector<float>> angle_;
  std::vector<std::vector<bool>> present_;
  std::vector<std::vector<int>> exits_at_;

  const Detection& d(const Point& p) const { return tracks_.frames[p.frame].found[p.index]; }

  // A track that ends where its grain leaves through the outlet: its last position in the opening and within
  // a diameter above the outlet line, or moving down so fast that it would be there a frame later (a small
  // grain falls farther than its diameter between two frames).
  bool leaves_at_outlet(const Track& tr) const {
    const Detection& last = d(tr.points.back());
    if (ends_at_outlet(last, geo_)) return true;
    if (tr.points.size() < 2) return false;
    const Point &p = tr.points[tr.points.size() - 2], &q = tr.points.back();
    const double dt = t_[q.frame] - t_[p.frame];
    if (!(dt > 0) || !(last.y < d(p).y)) return false;
    Detection next = last;
    next.x += (last.x - d(p).x) / dt * rep_.interval_median;
    next.y += (last.y - d(p).y) / dt * rep_.interval_median;
    return ends_at_outlet(next, geo_);
  }

  // Times from the first frame, and how regular the intervals are.
  void frame_times() {
    nf_ = static_cast<int>(tracks_.frames.size());
    rep_.frames = nf_;
    rep_.rows = tracks_.rows;
    rep_.time_offset = tracks_.frames.front().t;
    t_.resize(static_cast<size_t>(nf_));
    for (int k = 0; k < nf_; ++k) t_[k] = tracks_.frames[k].t - rep_.time_offset;
    std::vector<double> dt;
    for (int k = 1; k < nf_; ++k) dt.push_back(t_[k] - t_[k - 1]);
    rep_.interval_median = core::median(dt);
    if (!dt.empty()) {
      rep_.interval_min = *std::min_element(dt.begin(), dt.end());
      rep_.interval_max = *std::max_element(dt.begin(), dt.end());
    }
    for (double d : dt)
      if (std::fabs(d - rep_.interval_median) > 0.01 * rep_.interval_median) ++rep_.interval_changes;
  }

  // Tracks by the file's ids, then a track that breaks off away from the outlet joined to one starting near
  // where it ended, within max_gap frames: a grain whose id changed.
  void join_tracks() {
    std::map<long, Track> by_id;
    for (int k = 0; k < nf_; ++k) {
      const std::vector<Detection>& found = tracks_.frames[k].found;
      for (int i = 0; i < static_cast<int>(found.size()); ++i) {
        Track& tr = by_id[found[i].id];
        tr.id = found[i].id;
        tr.points.push_back({k, i});
      }
    }
    std::vector<Track> all;
    for (auto it = by_id.begin(); it != by_id.end(); it = by_id.erase(it))
      split_at_jumps(std::move(it->second), all);
    rep_.tracks = static_cast<long>(all.size());
    std::vector<std::vector<int>> starting(static_cast<size_t>(nf_));
    for (int i = 0; i < static_cast<int>(all.size()); ++i)
      starting[static_cast<size_t>(all[i].start())].push_back(i);
    std::vector<int> by_end(all.size());
    for (size_t i = 0; i < all.size(); ++i) by_end[i] = static_cast<int>(i);
    std::sort(by_end.begin(), by_end.end(), [&](int a, int b) { return all[a].end() < all[b].end(); });
    for (int ia : by_end) {
      Track& a = all[static_cast<size_t>(ia)];
      while (!a.joined && a.end() < nf_ - 1 && !leaves_at_outlet(a)) {
        const int best = best_continuation(all, starting, ia);
        if (best < 0) break;
        Track& b = all[static_cast<size_t>(best)];
        a.points.insert(a.points.end(), b.points.begin(), b.points.end());
        b.joined = true;
        ++rep_.joined;
      }
    }
    for (Track& tr : all)
      if (!tr.joined) grains_.push_back(std::move(tr));
    ng_ = static_cast<int>(grains_.size());
    rep_.grains = ng_;
  }

  // A track that jumps farther than a grain can move between two of its frames is two grains' (an id kept
  // across an exit and the re-injection at the top, or an id used again elsewhere): split there. A grain
  // moves at most four of its diameters, or twice the speed of a fall from the container's top, between them.
  void split_at_jumps(Track tr, std::vector<Track>& out) {
    const double fastest = 2 * std::sqrt(2 * core::length(model_.setup.gravity) * geo_.total_height);
    Track piece{tr.id, {}, false};
    for (const Point& p : tr.points) {
      if (!piece.points.empty()) {
        const Point& q = piece.points.back();
        const double reach = std::max(8 * d(p).r, fastest * (t_[p.frame] - t_[q.frame]));
        if (std::hypot(d(p).x - d(q).x, d(p).y - d(q).y) > reach) {
          out.push_back(std::move(piece));
          piece = Track{tr.id, {}, false};
          ++rep_.split;
        }
      }
      piece.points.push_back(p);
    }
    out.push_back(std::move(piece));
  }

  // The nearest track of the same species starting within max_gap frames after track ia ends, within
  // join_distance diameters; -1 when none.
  int best_continuation(const std::vector<Track>& all, const std::vector<std::vector<int>>& starting,
                        int ia) const {
    const Track& a = all[static_cast<size_t>(ia)];
    const Detection& last = d(a.points.back());
    int best = -1;
    double best_d = opt_.join_distance * 2 * last.r;
    for (int s = a.end() + 1; s <= std::min(nf_ - 1, a.end() + opt_.max_gap + 1); ++s)
      for (int ib : starting[static_cast<size_t>(s)]) {
        const Track& b = all[static_cast<size_t>(ib)];
        if (b.joined || ib == ia || d(b.points.front()).species != last.species) continue;
        const double dist = std::hypot(d(b.points.front()).x - last.x, d(b.points.front()).y - last.y);
        if (dist <= best_d) best_d = dist, best = ib;
      }
    return best;
  }

  // Each grain's size (the median of its detections) and species (the most frequent); then its slot.
  void grain_sizes() {
    grain_radius_.resize(static_cast<size_t>(ng_));
    grain_species_.resize(static_cast<size_t>(ng_));
    for (int g = 0; g < ng_; ++g) {
      std::vector<double> r;
      std::vector<int> count(model_.setup.species.size(), 0);
      for (const Point& p : grains_[g].points)
        r.push_back(d(p).r), ++count[static_cast<size_t>(d(p).species)];
      grain_radius_[g] = core::median(r);
      grain_species_[g] =
          static_cast<core::Species>(std::max_element(count.begin(), count.end()) - count.begin());
      rmax_ = std::max(rmax_, grain_radius_[g]);
    }
    assign_slots();
  }

  // The run's particles: as a simulation re-injects a grain that left, a grain that enters takes the slot of
  // one that left at least two frames before, of its species and its size (within 2%; the slot keeps its
  // first grain's radius), so a long film holds as many particles as the container does at once, not one per
  // grain that ever passed. Grains in their order of appearance; the first frame's keep the file's id order.
  void assign_slots() {
    std::vector<int> order(static_cast<size_t>(ng_));
    for (int g = 0; g < ng_; ++g) order[g] = g;
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return grains_[a].start() < grains_[b].start(); });
    slot_of_.assign(static_cast<size_t>(ng_), -1);
    std::vector<int> free_from;  // per slot: the first frame it may take another grain
    for (int g : order) {
      int slot = -1;
      for (int s = 0; s < static_cast<int>(free_from.size()) && slot < 0; ++s)
        if (free_from[s] <= grains_[g].start() && out_.species[s] == grain_species_[g] &&
            std::fabs(grain_radius_[g] / out_.radius[s] - 1) <= 0.02)
          slot = s;
      if (slot < 0) {
        slot = static_cast<int>(free_from.size());
        free_from.push_back(0);
        out_.radius.push_back(grain_radius_[g]);
        out_.species.push_back(grain_species_[g]);
        out_.track_id.push_back(grains_[g].id);
        held_.emplace_back();
      }
      free_from[slot] = grains_[g].end() + 3;
      slot_of_[g] = slot;
      held_[slot].push_back({grains_[g].start(), grains_[g].id});
    }
    n_ = static_cast<int>(free_from.size());
    rep_.particles = n_;
  }

  // The file's id of the grain in `slot` at frame k.
  long track_at(int slot, int k) const {
    const auto& h = held_[static_cast<size_t>(slot)];
    auto it = std::upper_bound(h.begin(), h.end(), std::make_pair(k, std::numeric_limits<long>::max()));
    return it == h.begin() ? h.front().second : std::prev(it)->second;
  }

  // Where each grain is at every frame: its detections, gaps of at most max_gap frames interpolated. Frame
  // by frame, each frame's detections released once placed when the caller asked (a frame's positions take
  // less room than its detections did).
  void grain_paths() {
    std::vector<std::vector<int>> slot_at(static_cast<size_t>(nf_));  // per detection
    for (int k = 0; k < nf_; ++k) slot_at[k].assign(tracks_.frames[k].found.size(), -1);
    for (int g = 0; g < ng_; ++g)
      for (const Point& p : grains_[g].points) slot_at[p.frame][p.index] = slot_of_[g];
    pos_.resize(static_cast<size_t>(nf_));
    angle_.resize(static_cast<size_t>(nf_));
    present_.resize(static_cast<size_t>(nf_));
    for (int k = 0; k < nf_; ++k) {
      pos_[k].assign(static_cast<size_t>(n_), {});
      angle_[k].assign(static_cast<size_t>(n_), 0.f);
      present_[k].assign(static_cast<size_t>(n_), false);
      std::vector<Detection>& found = tracks_.frames[k].found;
      for (size_t i = 0; i < found.size(); ++i) {
        const int s = slot_at[k][i];
        pos_[k][s] = {found[i].x, found[i].y};
        angle_[k][s] = static_cast<float>(found[i].angle);
        present_[k][s] = true;
      }
      std::vector<int>().swap(slot_at[k]);
      if (opt_.release_detections) std::vector<Detection>().swap(found);
    }
    for (int g = 0; g < ng_; ++g) {
      const auto& pts = grains_[g].points;
      for (size_t k = 0; k + 1 < pts.size(); ++k) fill_gap(slot_of_[g], pts[k], pts[k + 1]);
      if (grains_[g].start() > 0) ++rep_.entered;
    }
  }

  // The positions' noise, m: from the second differences across the grains' detections in three frames in a
  // row, x alone (gravity accelerates along y). For noise sigma and grains at rest or moving steadily they
  // are normal with deviation sqrt(6) sigma; the median of their size is robust to the collisions and falls
  // of the rest. Unless arrest_shift was given, the arrest check then asks no grain to hold stiller than 6
  // sigma (two positions' difference is normal with deviation sqrt(2) sigma per axis, and each of some
  // hundred grains near the outlet must pass: 6 sigma is its 1 - 1e-4 quantile).
  void measure_noise() {
    std::vector<double> dd;
    size_t points = 0;
    for (const Track& tr : grains_) points += tr.points.size();
    dd.reserve(points);
    for (const Track& tr : grains_)
      for (size_t k = 1; k + 1 < tr.points.size(); ++k) {
        const Point &a = tr.points[k - 1], &b = tr.points[k], &c = tr.points[k + 1];
        if (b.frame - a.frame == 1 && c.frame - b.frame == 1)
          dd.push_back(std::fabs(d(a).x - 2 * d(b).x + d(c).x));
      }
    if (dd.empty()) return;
    rep_.noise = core::median(std::move(dd)) / (0.6745 * std::sqrt(6.0));
    if (!opt_.arrest_shift_given) rep_.arrest_floor = 6 * rep_.noise;
  }

  void fill_gap(int g, const Point& p, const Point& q) {
    const int missing = q.frame - p.frame - 1;
    if (missing > opt_.max_gap) {
      ++rep_.long_gaps;
      return;
    }
    for (int f = p.frame + 1; f < q.frame; ++f) {
      const double w = (t_[f] - t_[p.frame]) / std::max(1e-12, t_[q.frame] - t_[p.frame]);
      const core::Vec2 a = pos_[p.frame][g], b = pos_[q.frame][g];
      pos_[f][g] = {a.x + w * (b.x - a.x), a.y + w * (b.y - a.y)};
      angle_[f][g] = static_cast<float>(angle_[p.frame][g] + w * (angle_[q.frame][g] - angle_[p.frame][g]));
      present_[f][g] = true;
      ++rep_.interpolated;
    }
  }

  // Where a grain is not seen it is parked far below the container, apart from every other (no contact, and
  // never between an arch and the outlet): a grid below the container, as wide as eight times its size
  // (trajectory readers refuse positions farther than ten times the container's size away).
  void park_unseen() {
    const double size = std::max(geo_.total_height, geo_.x_right - geo_.x_left), pitch = 2.5 * rmax_;
    const long cols = std::max(1L, static_cast<long>((geo_.x_right - geo_.x_left + 8 * size) / pitch));
    const long rows = static_cast<long>(7 * size / pitch);
    if (n_ > cols * rows)
      throw core::InputError(
          tracks_.source + ": " + std::to_string(n_) +
          " particles (grains in view at once, or tracks that "
          "never end) where a run holds at most " +
          std::to_string(cols * rows) +
          " for this container: join broken tracks (--join-distance, --max-gap) or import a "
          "shorter stretch");
    auto park = [&](int g) {
      return core::Vec2{geo_.x_left - 4 * size + (static_cast<double>(g % cols) + 0.5) * pitch,
                        -(geo_.total_height + 1.0) - static_cast<double>(g / cols) * pitch};
    };
    for (int k = 0; k < nf_; ++k)
      for (int g = 0; g < n_; ++g)
        if (!present_[k][g]) pos_[k][g] = park(g);
  }

  // Exits: the centre wholly below the outlet line, or a track that ends inside the outlet.
  void find_exits() {
    exits_at_.assign(static_cast<size_t>(nf_), {});
    for (int g = 0; g < ng_; ++g) {
      int exit_frame = -1;
      for (const Point& p : grains_[g].points)
        if (d(p).y < -grain_radius_[g]) {
          exit_frame = p.frame;
          ++rep_.exits_below;
          break;
        }
      if (exit_frame < 0 && grains_[g].end() < nf_ - 1) {
        if (leaves_at_outlet(grains_[g])) {
          exit_frame = grains_[g].end() + 1;
          ++rep_.exits_lost;
        } else {
          ++rep_.left_view;
        }
      }
      if (exit_frame >= 0) exits_at_[static_cast<size_t>(exit_frame)].push_back(slot_of_[g]);
    }
  }

  // A calibration that cannot be the experiment's is refused rather than imported: most grains leaving in one
  // frame (a wrong --y-up or --origin puts them below the outlet), or grains overlapping or floating apart (a
  // wrong --scale): in a clogging hopper neighbours touch, so each grain's nearest neighbour stands about the
  // sum of their radii away (the median over the first frames, between half and three times it).
  void check_calibration() const {
    const std::string fix =
        ": check --scale, --origin and --y-up (or the calibration detect wrote beside the tracks)";
    for (int k = 0; k < nf_; ++k) {
      const long leaving = static_cast<long>(exits_at_[k].size());
      if (leaving <= 10) continue;
      long seen = 0;
      for (int g = 0; g < n_; ++g) seen += present_[k][g];
      if (leaving > seen / 4)
        throw core::InputError(
            tracks_.source + ": " + std::to_string(leaving) + " of " + std::to_string(seen) +
            " grains leave through the outlet at once (at t = " + core::format_g(t_[k], 4) +
            " s); a discharge lets a few through a frame" + fix);
    }
    if (tracks_.has_radius && ng_ > 0) {
      std::vector<double> size;
      for (int g = 0; g < ng_; ++g)
        size.push_back(
            grain_radius_[g] /
            model_.setup.species[static_cast<size_t>(core::species_index(grain_species_[g]))].radius);
      const double m = core::median(size);
      if (m < 0.5 || m > 2)
        throw core::InputError(tracks_.source + ": the grains measure " + core::format_g(m, 3) +
                               " times their species' radius in the geometry scene (the median)" + fix);
    }
    std::vector<double> ratio;
    for (int k = 0; k < std::min(nf_, 5); ++k) {
      std::vector<int> seen;  // the grains of this frame (a long film has many more grains than a frame)
      for (int g = 0; g < n_; ++g)
        if (present_[k][g]) seen.push_back(g);
      for (int g : seen) {
        double nearest = INFINITY;
        for (int h : seen)
          if (h != g)
            nearest =
                std::min(nearest, core::length(pos_[k][g] - pos_[k][h]) / (out_.radius[g] + out_.radius[h]));
        if (std::isfinite(nearest)) ratio.push_back(nearest);
      }
    }
    if (ratio.size() < 10) return;
    const double m = core::median(ratio);
    if (m < 0.5 || m > 3)
      throw core::InputError(
          tracks_.source + ": grains " + (m < 0.5 ? "overlap" : "float apart") +
          ": a grain's nearest neighbour stands " + core::format_g(m, 3) +
          " times the sum of their radii away (median over the first frames; touching grains "
          "give about 1)" +
          fix);
  }

  // The grains' tracks are not needed past here: their memory goes before the frames are built.
  void release() { std::vector<Track>().swap(grains_); }

  // At rest at frame k: the arch and the grains no farther from the outlet's centre held still over
  // arrest_hold.
  bool at_rest(int k, const std::vector<int>& arch) const {
    if (arch.empty() || k == 0) return false;
    const core::Scene& scene = model_.scene;
    int j = k - 1;
    while (j > 0 && t_[k] - t_[j] < scene.arrest_hold) --j;
    double reach = 0;
    for (int id : arch) reach = std::max(reach, core::length(pos_[k][id]) + out_.radius[id]);
    for (int g = 0; g < n_; ++g) {
      if (!present_[k][g] || core::length(pos_[k][g]) > reach) continue;
      if (!present_[j][g]) return false;
      const core::Vec2 d = pos_[k][g] - pos_[j][g];
      const double limit = std::max(scene.arrest_shift * out_.radius[g], rep_.arrest_floor);
      if (core::dot(d, d) > limit * limit) return false;
    }
    return true;
  }

  // The frames before frame k, from the arch's formation on, show the clog confirmed at k as forming: the
  // arch from the instant it stood, as a simulated run's trajectory has it (app/services/hindsight.h).
  void show_forming(int k, const core::ClogState& st) {
    if (st.arch.empty() || std::isnan(st.formed)) return;
    for (int j = k - 1; j >= 0 && t_[j] >= st.formed - 1e-9; --j) {
      core::Frame& f = out_.frames[static_cast<size_t>(j)];
      if (f.clog_open) break;
      if (!std::all_of(st.arch.begin(), st.arch.end(), [&](int g) { return present_[j][g]; })) continue;
      f.arch = st.arch;
      f.arch_forming = true;
      f.clog_number = st.number;
    }
  }

  // Clogs and arches, frame by frame, by the simulation's rules (no clog rule: nothing removes an arch here).
  void clogs_and_arches() {
    const bool driven = model_.setup.drive.kick_impulse_max > 0 || model_.setup.drive.vibrating();
    core::ClogTracker tracker(model_.scene.clog_min_gap, 0, driven);
    std::vector<std::int64_t> exits(model_.setup.species.size(), 0);
    out_.frames.resize(static_cast<size_t>(nf_));
    out_.between.resize(static_cast<size_t>(nf_));
    std::vector<int> held_arch;  // the open clog's arch, and the frame it was last seen at
    int held_frame = -1;
    auto close_arch = [&](const core::StepEvents& ev) {
      for (size_t c = 0; c < ev.clogs_closed.size(); ++c) {
        if (held_arch.empty() || held_frame < 0) continue;
        ClogArch a;
        a.clog = static_cast<int>(tracker.clogs().size() - ev.clogs_closed.size() + c + 1);
        a.t = t_[held_frame];
        a.ids = held_arch;
        for (int id : held_arch) a.track_ids.push_back(track_at(id, held_frame));
        a.descriptors = core::arch_descriptors(held_arch, pos_[held_frame], out_.radius);
        out_.clog_arches.push_back(std::move(a));
        held_arch.clear();
        held_frame = -1;
      }
    };
    for (int k = 0; k < nf_; ++k) {
      core::throw_if_interrupted();
      core::StepEvents& ev = out_.between[k];
      for (int g : exits_at_[k]) {
        ev.exits.push_back({t_[k], g, out_.species[g]});
        out_.events.exits.push_back(ev.exits.back());
        ++exits[static_cast<size_t>(core::species_index(out_.species[g]))];
        tracker.on_exit(t_[k], ev);
      }
      close_arch(ev);
      std::vector<int> arch =
          arch_by_distance(pos_[k], out_.radius, present_[k], model_, opt_.contact_tolerance);
      if (!arch.empty()) ++rep_.frames_with_arch;
      tracker.on_rest_check(t_[k], at_rest(k, arch), arch);
      tracker.on_step_end(
          t_[k], [&] { return arch; }, ev);
      const core::ClogState& st = tracker.state();
      if (st.open) {
        ++rep_.frames_clogged;
        rep_.frames_clogged_with_arch += !arch.empty();
      } else {
        rep_.frames_flowing_with_arch += !arch.empty();
      }
      // An arch is of grains in the frame: one whose member is not seen (its track ended without an exit,
      // or a gap) is neither drawn nor recorded at that frame; the clog keeps the arch as last seen whole.
      const bool whole = std::all_of(st.arch.begin(), st.arch.end(), [&](int g) { return present_[k][g]; });
      if (st.open && !st.arch.empty() && whole) held_arch = st.arch, held_frame = k;
      if (!ev.clogs_opened.empty()) show_forming(k, st);
      core::Frame& f = out_.frames[k];
      f.t = t_[k];
      f.step = static_cast<std::uint64_t>(k);
      f.clog_open = st.open;
      f.clog_number = st.number;
      f.clog_start = st.start;
      f.clog_arrested = st.arrested;
      if (st.open && whole) f.arch = st.arch;
      f.rule_due_in = INFINITY;
      f.since_last_exit = tracker.since_last(t_[k]);
      f.exits = exits;
    }
    tracker.finish(t_[nf_ - 1], out_.after);
    close_arch(out_.after);
    out_.events.clogs = tracker.clogs();
  }
};

}  // namespace

void Imported::particles_at(size_t k, std::vector<core::Particle>& out) const {
  const size_t n = radius.size(), nf = paths.t.size();
  const std::vector<core::Vec2>& pos = paths.pos[k];
  out.resize(n);
  for (size_t g = 0; g < n; ++g) {
    core::Particle& p = out[g];
    p.radius = static_cast<float>(radius[g]);
    p.species = species[g];
    p.force = 0;
    p.vx = p.vy = 0;
    p.x = static_cast<float>(pos[g].x);
    p.y = static_cast<float>(pos[g].y);
    p.angle = 0;
    if (!paths.present[k][g]) continue;
    p.angle = paths.angle[k][g];
    const size_t a = k > 0 && paths.present[k - 1][g] ? k - 1 : k;
    const size_t b = k + 1 < nf && paths.present[k + 1][g] ? k + 1 : k;
    if (b > a) {
      const double dt = paths.t[b] - paths.t[a];
      p.vx = static_cast<float>((paths.pos[b][g].x - paths.pos[a][g].x) / dt);
      p.vy = static_cast<float>((paths.pos[b][g].y - paths.pos[a][g].y) / dt);
    }
  }
}

Imported import_tracks(Tracks& tracks, const core::Model& model, const ImportOptions& opt) {
  return Importer(tracks, model, opt).run();
}

}  // namespace lab
