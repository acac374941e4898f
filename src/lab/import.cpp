// A lab run from tracked particles (lab/import.h): tracks joined into grains, their paths, exits, then clogs
// and arches by the simulation's own rules, one step of the Importer each. Over 400 lines because the steps
// share one state (every grain's path at every frame) and read best in order; contacts and arches by distance
// are the lab's own geometry, in lab/contacts.cpp.
#include "lab/import.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>

#include "core/clog.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/median.h"
#include "lab/contacts.h"

namespace lab {

namespace {

// A detection where its track needs it: the tracks' points lie one track after another (on disk, as the
// detections by frame do), so a pass over the grains reads them in order.
struct Point {
  Detection det;
  int frame;
  int index;  // of the detection in its frame
};
struct Track {
  Track(long i, std::span<Point> p) : id(i), points(p), first(p.front().frame), last(p.back().frame) {}
  long id;
  std::span<Point> points;  // in frame order
  bool joined = false;      // merged into another
  std::vector<int> chain;   // the tracks joined after this one, in order (while joining)
  int first, last;          // frames (kept here: reading them from the points would bring their pages in)
  int start() const { return first; }
  int end() const { return last; }
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
    park_unseen();
    check_calibration();
    release();
    clogs_and_arches();
    paths_.t = std::move(t_);
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
  std::vector<Track> grains_;      // their points in track_points_, or grain_points_ when joined
  io::Spill<Point> track_points_;  // by the file's ids
  io::Spill<Point> grain_points_;  // of the grains joined from several tracks
  std::vector<std::vector<std::pair<long, int>>> pieces_;  // per grain: its tracks' (file id, first frame)
  std::vector<double> grain_radius_;
  std::vector<core::Species> grain_species_;
  std::vector<int> slot_of_;                             // per grain
  std::vector<std::vector<std::pair<int, long>>> held_;  // per slot: (first frame, file id) of its grains
  Paths& paths_ = out_.paths;
  std::vector<std::vector<int>> exits_at_;

  static const Detection& d(const Point& p) { return p.det; }
  core::Vec2& pos(int k, int g) const { return paths_.pos[static_cast<size_t>(k) * paths_.n + g]; }
  float& ang(int k, int g) const { return paths_.angle[static_cast<size_t>(k) * paths_.n + g]; }
  std::uint8_t& seen(int k, int g) const { return paths_.present[static_cast<size_t>(k) * paths_.n + g]; }
  // The pages of the detections, the grains' points and the paths read so far leave memory (they stay on
  // disk) once about kTouched bytes of them were read: a pass over frames or over grains reads them one
  // after another; filling a grain's gap reaches into the paths a page a frame.
  static constexpr size_t kTouched = size_t{16} << 20;
  static constexpr size_t kFaultAround = size_t{64} << 10;  // what one read brings in (Linux's fault-around)
  mutable size_t touched_ = 0;
  void breathe(size_t bytes) const {
    touched_ += bytes;
    if (touched_ < kTouched) return;
    touched_ = 0;
    tracks_.detections.release();
    track_points_.release();
    grain_points_.release();
    paths_.release();
  }
  void breathe_frame(int k) const {
    breathe(tracks_.frames[k].found.size() * sizeof(Detection) + paths_.n * (sizeof(core::Vec2) + 5));
  }
  void breathe_grain(const Track& tr) const { breathe(tr.points.size() * sizeof(Point)); }
  void breathe_out() const { breathe(kTouched); }

  // A track that ends where its grain leaves through the outlet: its last position in the opening and within
  // a diameter above the outlet line, or moving down so fast that it would be there a frame later (a small
  // grain falls farther than its diameter between two frames).
  bool leaves_at_outlet(const Track& tr) const {
    return leaves_at_outlet(tr.points.back(),
                            tr.points.size() < 2 ? nullptr : &tr.points[tr.points.size() - 2]);
  }
  // ... its last point q, the one before p (nullptr: none).
  bool leaves_at_outlet(const Point& q, const Point* before) const {
    const Detection& last = d(q);
    if (ends_at_outlet(last, geo_)) return true;
    if (!before) return false;
    const Point& p = *before;
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
  // where it ended, within max_gap frames: a grain whose id changed. The points are copied onto disk track
  // by track (by the file's ids).
  void join_tracks() {
    std::unordered_map<long, std::size_t> next;  // id -> its points' count, then where its next one goes
    for (int k = 0; k < nf_; ++k) {
      for (const Detection& det : tracks_.frames[k].found) ++next[det.id];
      breathe_frame(k);
    }
    std::vector<long> ids;
    ids.reserve(next.size());
    for (const auto& [id, n] : next) ids.push_back(id);
    std::sort(ids.begin(), ids.end());
    std::vector<std::size_t> first(ids.size() + 1, 0);  // the ids' points' places, in the ids' order
    for (size_t i = 0; i < ids.size(); ++i) first[i + 1] = first[i] + std::exchange(next[ids[i]], first[i]);
    track_points_ = io::Spill<Point>(opt_.spill_dir);
    io::Spill<Point>& by_id = track_points_;
    by_id.resize(first.back());
    for (int k = 0; k < nf_; ++k) {
      const std::span<Detection> found = tracks_.frames[k].found;
      for (int i = 0; i < static_cast<int>(found.size()); ++i)
        by_id[next.find(found[i].id)->second++] = {found[i], k, i};
      breathe_frame(k);
      if (k % 1024 == 1023) by_id.release();
    }
    std::vector<Track> all;
    for (size_t i = 0; i < ids.size(); ++i) {
      split_at_jumps(Track{ids[i], std::span<Point>(by_id.data() + first[i], first[i + 1] - first[i])}, all);
      if (first[i] / 8192 != first[i + 1] / 8192) by_id.release();
    }
    by_id.release();
    rep_.tracks = static_cast<long>(all.size());
    std::vector<std::vector<int>> starting(static_cast<size_t>(nf_));
    for (int i = 0; i < static_cast<int>(all.size()); ++i)
      starting[static_cast<size_t>(all[i].start())].push_back(i);
    std::vector<int> by_end(all.size());
    for (size_t i = 0; i < all.size(); ++i) by_end[i] = static_cast<int>(i);
    std::sort(by_end.begin(), by_end.end(), [&](int a, int b) { return all[a].end() < all[b].end(); });
    for (int ia : by_end) {
      Track& a = all[static_cast<size_t>(ia)];
      if (a.joined) continue;
      auto before_last = [&](const Track& tail) {  // the chain's point before its last (nullptr: one point)
        if (tail.points.size() >= 2) return &tail.points[tail.points.size() - 2];
        return a.chain.size() >= 2   ? &all[static_cast<size_t>(a.chain[a.chain.size() - 2])].points.back()
               : a.chain.size() == 1 ? &a.points.back()
                                     : nullptr;
      };
      for (;;) {
        const Track& tail = a.chain.empty() ? a : all[static_cast<size_t>(a.chain.back())];
        if (tail.end() >= nf_ - 1 || leaves_at_outlet(tail.points.back(), before_last(tail))) break;
        const int best = best_continuation(all, starting, ia, tail);
        if (best < 0) break;
        all[static_cast<size_t>(best)].joined = true;
        a.chain.push_back(best);
        ++rep_.joined;
      }
      breathe(kFaultAround * 8 * (a.chain.size() + 1));
    }
    grains_from(all);
    ng_ = static_cast<int>(grains_.size());
    rep_.grains = ng_;
  }

  // The grains: each track not joined to another, with those joined after it. A track joined to none keeps
  // its points where they are; a grain of several has them copied one after another.
  void grains_from(std::vector<Track>& all) {
    size_t joined = 0;
    for (const Track& tr : all)
      if (!tr.joined && !tr.chain.empty()) {
        joined += tr.points.size();
        for (int b : tr.chain) joined += all[static_cast<size_t>(b)].points.size();
      }
    grain_points_ = io::Spill<Point>(opt_.spill_dir);
    grain_points_.resize(joined);
    std::size_t at = 0;
    for (Track& tr : all) {
      if (tr.joined) continue;
      pieces_.push_back({{tr.id, tr.start()}});
      if (tr.chain.empty()) {
        grains_.push_back(tr);  // its frames as kept (reading them again would bring pages in)
        continue;
      }
      const std::size_t first = at;
      auto copy = [&](const Track& piece) {
        std::copy(piece.points.begin(), piece.points.end(), grain_points_.data() + at);
        at += piece.points.size();
        breathe(2 * piece.points.size() * sizeof(Point));
      };
      copy(tr);
      for (int b : tr.chain) {
        copy(all[static_cast<size_t>(b)]);
        pieces_.back().push_back({all[static_cast<size_t>(b)].id, all[static_cast<size_t>(b)].start()});
      }
      grains_.push_back(Track{tr.id, std::span<Point>(grain_points_.data() + first, at - first)});
    }
  }

  // A track that jumps farther than a grain can move between two of its frames is two grains' (an id kept
  // across an exit and the re-injection at the top, or an id used again elsewhere): split there. A grain
  // moves at most four of its diameters, or twice the speed of a fall from the container's top, between them.
  void split_at_jumps(const Track& tr, std::vector<Track>& out) {
    const double fastest = 2 * std::sqrt(2 * core::length(model_.setup.gravity) * geo_.total_height);
    std::size_t from = 0;
    for (std::size_t k = 1; k < tr.points.size(); ++k) {
      const Point &p = tr.points[k], &q = tr.points[k - 1];
      const double reach = std::max(8 * d(p).r, fastest * (t_[p.frame] - t_[q.frame]));
      if (std::hypot(d(p).x - d(q).x, d(p).y - d(q).y) > reach) {
        out.push_back(Track{tr.id, tr.points.subspan(from, k - from)});
        from = k;
        ++rep_.split;
      }
    }
    out.push_back(Track{tr.id, tr.points.subspan(from)});
  }

  // The nearest track of the same species starting within max_gap frames after track ia ends (with those
  // joined to it: its tail), within
  // join_distance diameters; -1 when none.
  int best_continuation(const std::vector<Track>& all, const std::vector<std::vector<int>>& starting, int ia,
                        const Track& tail) const {
    const Detection& last = d(tail.points.back());
    int best = -1;
    double best_d = opt_.join_distance * 2 * last.r;
    for (int s = tail.end() + 1; s <= std::min(nf_ - 1, tail.end() + opt_.max_gap + 1); ++s)
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
      breathe_grain(grains_[g]);
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

  // Where each grain is at every frame: its detections, gaps of at most max_gap frames interpolated, kept on
  // disk as the detections are (frame k's particle g at k * n + g).
  void grain_paths() {
    // Each detection's particle: by its file id, the track of that id it falls in (they follow each other).
    std::unordered_map<long, std::vector<std::pair<int, int>>>
        slots;  // id -> (first frame, slot) of its tracks
    for (int g = 0; g < ng_; ++g)
      for (const auto& [id, start] : pieces_[static_cast<size_t>(g)])
        slots[id].push_back({start, slot_of_[g]});
    for (auto& [id, v] : slots) std::sort(v.begin(), v.end());
    auto slot_at = [&](long id, int k) {
      const auto& v = slots.find(id)->second;
      return std::prev(
                 std::upper_bound(v.begin(), v.end(), std::make_pair(k, std::numeric_limits<int>::max())))
          ->second;
    };
    paths_ = Paths(opt_.spill_dir);
    paths_.n = static_cast<size_t>(n_);
    const size_t cells = static_cast<size_t>(nf_) * paths_.n;
    paths_.pos.resize(cells);
    paths_.angle.resize(cells);
    paths_.present.resize(cells);
    for (int k = 0; k < nf_; ++k) {
      const TrackFrame& f = tracks_.frames[k];
      for (size_t i = 0; i < f.found.size(); ++i) {
        const int s = slot_at(f.found[i].id, k);
        pos(k, s) = {f.found[i].x, f.found[i].y};
        ang(k, s) = static_cast<float>(f.found[i].angle);
        seen(k, s) = 1;
      }
      breathe_frame(k);
    }
    for (int g = 0; g < ng_; ++g) {
      const auto& pts = grains_[g].points;
      for (size_t k = 0; k + 1 < pts.size(); ++k) fill_gap(slot_of_[g], pts[k], pts[k + 1]);
      if (grains_[g].start() > 0) ++rep_.entered;
      breathe_grain(grains_[g]);
    }
    breathe_out();
  }

  // The positions' noise, m: from the second differences across the grains' detections in three frames in a
  // row, x alone (gravity accelerates along y). For noise sigma and grains at rest or moving steadily they
  // are normal with deviation sqrt(6) sigma; the median of their size is robust to the collisions and falls
  // of the rest. Unless arrest_shift was given, the arrest check then asks no grain to hold stiller than 6
  // sigma (two positions' difference is normal with deviation sqrt(2) sigma per axis, and each of some
  // hundred grains near the outlet must pass: 6 sigma is its 1 - 1e-4 quantile).
  void measure_noise() {
    io::Spill<double> dd(opt_.spill_dir);
    for (int g = 0; g < ng_; ++g) {
      const Track& tr = grains_[g];
      for (size_t k = 1; k + 1 < tr.points.size(); ++k) {
        const Point &a = tr.points[k - 1], &b = tr.points[k], &c = tr.points[k + 1];
        if (b.frame - a.frame == 1 && c.frame - b.frame == 1)
          dd.push_back(std::fabs(d(a).x - 2 * d(b).x + d(c).x));
      }
      breathe_grain(grains_[g]);
      if (g % 64 == 63) dd.release();
    }
    if (dd.empty()) return;
    const size_t n = dd.size();
    const double median = n % 2 ? io::kth_smallest(dd, n / 2)
                                : 0.5 * (io::kth_smallest(dd, n / 2 - 1) + io::kth_smallest(dd, n / 2));
    rep_.noise = median / (0.6745 * std::sqrt(6.0));
    if (!opt_.arrest_shift_given) rep_.arrest_floor = 6 * rep_.noise;
  }

  void fill_gap(int g, const Point& p, const Point& q) {
    const int missing = q.frame - p.frame - 1;
    if (missing > opt_.max_gap) {
      ++rep_.long_gaps;
      return;
    }
    if (missing > 0) breathe(kFaultAround * static_cast<size_t>(missing + 2));
    for (int f = p.frame + 1; f < q.frame; ++f) {
      const double w = (t_[f] - t_[p.frame]) / std::max(1e-12, t_[q.frame] - t_[p.frame]);
      const core::Vec2 a = pos(p.frame, g), b = pos(q.frame, g);
      pos(f, g) = {a.x + w * (b.x - a.x), a.y + w * (b.y - a.y)};
      ang(f, g) = static_cast<float>(ang(p.frame, g) + w * (ang(q.frame, g) - ang(p.frame, g)));
      seen(f, g) = true;
      ++rep_.interpolated;
    }
  }

  // The paths (grain_paths, once the run's particles are known to fit), and where a grain is not seen it is
  // parked far below the container, apart from every other (no contact, and never between an arch and the
  // outlet): a grid below the container, as wide as eight times its size (trajectory readers refuse
  // positions farther than ten times the container's size away).
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
    grain_paths();
    auto park = [&](int g) {
      return core::Vec2{geo_.x_left - 4 * size + (static_cast<double>(g % cols) + 0.5) * pitch,
                        -(geo_.total_height + 1.0) - static_cast<double>(g / cols) * pitch};
    };
    for (int k = 0; k < nf_; ++k) {
      for (int g = 0; g < n_; ++g)
        if (!seen(k, g)) pos(k, g) = park(g);
      breathe_frame(k);
    }
    breathe_out();
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
      breathe_grain(grains_[g]);
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
      breathe_frame(k);
      long shown = 0;
      for (int g = 0; g < n_; ++g) shown += seen(k, g);
      if (leaving > shown / 4)
        throw core::InputError(
            tracks_.source + ": " + std::to_string(leaving) + " of " + std::to_string(shown) +
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
      std::vector<int> shown;  // the grains of this frame (a long film has many more grains than a frame)
      for (int g = 0; g < n_; ++g)
        if (seen(k, g)) shown.push_back(g);
      for (int g : shown) {
        double nearest = INFINITY;
        for (int h : shown)
          if (h != g)
            nearest =
                std::min(nearest, core::length(pos(k, g) - pos(k, h)) / (out_.radius[g] + out_.radius[h]));
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
  void release() {
    std::vector<Track>().swap(grains_);
    track_points_ = io::Spill<Point>();
    grain_points_ = io::Spill<Point>();
    std::vector<std::vector<std::pair<long, int>>>().swap(pieces_);
  }

  // At rest at frame k: the arch and the grains no farther from the outlet's centre held still over
  // arrest_hold.
  bool at_rest(int k, const std::vector<int>& arch) const {
    if (arch.empty() || k == 0) return false;
    int j = k - 1;
    while (j > 0 && t_[k] - t_[j] < model_.scene.arrest_hold) --j;
    return still_between(k, j, reach_of(k, arch));
  }

  // How far from the outlet's centre the grains of `arch` reach at frame k.
  double reach_of(int k, const std::vector<int>& arch) const {
    double reach = 0;
    for (int id : arch) reach = std::max(reach, core::length(pos(k, id)) + out_.radius[id]);
    return reach;
  }

  // Every grain seen at frame k no farther than `reach` from the outlet's centre was seen at frame j and
  // moved less than the arrest shift (or the noise's floor) between them.
  bool still_between(int k, int j, double reach) const {
    for (int g = 0; g < n_; ++g) {
      if (!seen(k, g) || core::length(pos(k, g)) > reach) continue;
      if (!seen(j, g)) return false;
      const core::Vec2 d = pos(k, g) - pos(j, g);
      const double limit = std::max(model_.scene.arrest_shift * out_.radius[g], rep_.arrest_floor);
      if (core::dot(d, d) > limit * limit) return false;
    }
    return true;
  }

  // The arch at frame k on positions averaged over the frames before it at which the grains around the
  // outlet stay where they are at k (at most kRestWindow): a position's noise shrinks with the square root
  // of their number, so a noisy film's resting arch is found as a clean one's (a bond of a touching pair is
  // otherwise lost in one frame of twelve at 0.05 d of noise, and an arch of ten grains takes a detour).
  // Of grains seen at k; empty if none blocks the outlet there. `mean` gets the averaged positions.
  std::vector<int> arch_at_rest(int k, const std::vector<int>& held, std::vector<core::Vec2>& mean) const {
    constexpr double kRestWindow = 1.0;   // s
    constexpr double kNoiseMargin = 2.5;  // standard deviations of the gap's noise
    const double reach = reach_of(k, held);
    int first = k;
    for (int j = k - 1; j >= 0 && t_[k] - t_[j] <= kRestWindow && still_between(k, j, reach); --j) first = j;
    std::vector<bool> present(static_cast<size_t>(n_));
    mean.assign(static_cast<size_t>(n_), core::Vec2{0, 0});
    for (int g = 0; g < n_; ++g) {
      present[static_cast<size_t>(g)] = seen(k, g);
      mean[static_cast<size_t>(g)] = pos(k, g);  // a grain not seen keeps where the paths park it
      if (!seen(k, g)) continue;
      mean[static_cast<size_t>(g)] = core::Vec2{0, 0};
      int count = 0;
      for (int j = first; j <= k; ++j)
        if (seen(j, g)) mean[static_cast<size_t>(g)] = mean[static_cast<size_t>(g)] + pos(j, g), ++count;
      mean[static_cast<size_t>(g)] = (1.0 / count) * mean[static_cast<size_t>(g)];
    }
    // The gap between two averaged positions still carries sqrt(2 / frames) of the noise: a contact is
    // lost to it less than once in a hundred bonds when the tolerance is 2.5 times that (as a fraction of
    // the smallest diameter), if that is more than the tolerance asked for.
    double smallest = INFINITY;
    for (const core::SpeciesDef& s : model_.setup.species) smallest = std::min(smallest, s.radius_min);
    const double margin = kNoiseMargin * std::sqrt(2.0 / (k - first + 1)) * rep_.noise / (2 * smallest);
    return arch_by_distance(mean, out_.radius, present, model_, std::max(opt_.contact_tolerance, margin));
  }

  // The frames before frame k, from the arch's formation on, show the clog confirmed at k as forming: the
  // arch from the instant it stood, as a simulated run's trajectory has it (app/services/hindsight.h).
  void show_forming(int k, const core::ClogState& st) {
    if (st.arch.empty() || std::isnan(st.formed)) return;
    for (int j = k - 1; j >= 0 && t_[j] >= st.formed - 1e-9; --j) {
      core::Frame& f = out_.frames[static_cast<size_t>(j)];
      if (f.clog_open) break;
      if (!std::all_of(st.arch.begin(), st.arch.end(), [&](int g) { return seen(j, g); })) continue;
      f.arch = st.arch;
      f.arch_forming = true;
      f.clog_number = st.number;
    }
  }

  // Frame k's positions and which particles are seen.
  void frame_at(int k, std::vector<core::Vec2>& p, std::vector<bool>& present) const {
    p.assign(&pos(k, 0), &pos(k, 0) + n_);
    present.resize(static_cast<size_t>(n_));
    for (int g = 0; g < n_; ++g) present[static_cast<size_t>(g)] = seen(k, g);
  }

  // Clogs and arches, frame by frame, by the simulation's rules (no clog rule: nothing removes an arch here).
  void clogs_and_arches() {
    const bool driven = model_.setup.drive.kick_impulse_max > 0 || model_.setup.drive.vibrating();
    core::ClogTracker tracker(model_.scene.clog_min_gap, 0, driven);
    std::vector<std::int64_t> exits(model_.setup.species.size(), 0);
    out_.frames.resize(static_cast<size_t>(nf_));
    out_.between.resize(static_cast<size_t>(nf_));
    // The open clog's arch and the frame it was taken at: the arch a clog stood on, not a chain of its
    // breaking (below).
    std::vector<int> held_arch;
    int held_frame = -1;
    std::vector<core::Vec2> frame_pos;
    std::vector<bool> frame_present;
    auto close_arch = [&](const core::StepEvents& ev) {
      for (size_t c = 0; c < ev.clogs_closed.size(); ++c) {
        if (held_arch.empty() || held_frame < 0) continue;
        ClogArch a;
        a.clog = static_cast<int>(tracker.clogs().size() - ev.clogs_closed.size() + c + 1);
        a.t = t_[held_frame];
        a.ids = arch_at_rest(held_frame, held_arch, frame_pos);
        if (a.ids.empty()) {
          a.ids = held_arch;
          frame_at(held_frame, frame_pos, frame_present);
        }
        for (int id : a.ids) a.track_ids.push_back(track_at(id, held_frame));
        a.descriptors = core::arch_descriptors(a.ids, frame_pos, out_.radius);
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
      frame_at(k, frame_pos, frame_present);
      std::vector<int> arch =
          arch_by_distance(frame_pos, out_.radius, frame_present, model_, opt_.contact_tolerance);
      if (!arch.empty()) ++rep_.frames_with_arch;
      const bool rest = at_rest(k, arch);
      tracker.on_rest_check(t_[k], rest, arch);
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
      // or a gap) is neither drawn nor recorded at that frame. The clog keeps the arch last seen whole at
      // rest; if it never was, the first seen whole (a clog a drive breaks within a few frames: its last
      // frames' contacts are a chain of its breaking, one the simulation's forces do not carry).
      const bool whole = std::all_of(st.arch.begin(), st.arch.end(), [&](int g) { return seen(k, g); });
      if (st.open && !st.arch.empty() && whole && (rest || held_frame < 0))
        held_arch = st.arch, held_frame = k;
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
      breathe_frame(k);
    }
    breathe_out();
    tracker.finish(t_[nf_ - 1], out_.after);
    close_arch(out_.after);
    out_.events.clogs = tracker.clogs();
  }
};

}  // namespace

void Imported::particles_at(size_t k, std::vector<core::Particle>& out) const {
  const size_t n = radius.size(), nf = paths.t.size();
  out.resize(n);
  for (size_t g = 0; g < n; ++g) {
    core::Particle& p = out[g];
    const core::Vec2 at = paths.pos_at(k, g);
    p.radius = static_cast<float>(radius[g]);
    p.species = species[g];
    p.force = 0;
    p.vx = p.vy = 0;
    p.x = static_cast<float>(at.x);
    p.y = static_cast<float>(at.y);
    p.angle = 0;
    if (!paths.seen_at(k, g)) continue;
    p.angle = paths.angle_at(k, g);
    const size_t a = k > 0 && paths.seen_at(k - 1, g) ? k - 1 : k;
    const size_t b = k + 1 < nf && paths.seen_at(k + 1, g) ? k + 1 : k;
    if (b > a) {
      const double dt = paths.t[b] - paths.t[a];
      p.vx = static_cast<float>((paths.pos_at(b, g).x - paths.pos_at(a, g).x) / dt);
      p.vy = static_cast<float>((paths.pos_at(b, g).y - paths.pos_at(a, g).y) / dt);
    }
  }
  if (k % 1024 == 1023) paths.release();
}

Imported import_tracks(Tracks& tracks, const core::Model& model, const ImportOptions& opt) {
  return Importer(tracks, model, opt).run();
}

}  // namespace lab
