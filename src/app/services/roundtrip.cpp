// The round trip of detect and import against a recording (app/services/roundtrip.h).
#include "app/services/roundtrip.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <toml++/toml.h>

#include "analysis/stats.h"
#include "app/services/lab.h"
#include "core/arch.h"
#include "core/error.h"
#include "core/median.h"
#include "io/output.h"
#include "io/run.h"
#include "lab/import.h"

namespace app {

namespace fs = std::filesystem;

namespace {

double quantile_of(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace

namespace {

// What the round trip compares: the recording's truth, and the tracks and run the camera's picture of it
// gave.
struct Trip {
  Calibration cal;
  core::Model model;
  int width = 0, height = 0;
  lab::Tracks tracks;
  lab::Imported im;
  // Per frame of the tracks: file id -> the true grain it was matched to.
  std::vector<std::map<long, int>> truth_of;
};

// Grains, frame by frame: each detection matched to the nearest true grain within half its radius; recall,
// precision, position errors and id switches into `row`.
void score_grains(const io::Trajectory& truth, Trip& trip, RoundTripRow& row) {
  const lab::Tracks& tracks = trip.tracks;
  const Calibration& cal = trip.cal;
  long tp = 0, fn = 0, fp = 0, grain_frames = 0;
  std::vector<double> errors;
  std::map<int, long> last_track;  // true grain -> the track it was last matched to
  trip.truth_of.assign(tracks.frames.size(), {});
  auto whole_in_view = [&](const core::Particle& p) {
    const core::Vec2 q = cal.to_pixels({p.x, p.y});
    const double px = q.x, py = q.y, r = p.radius / cal.scale;
    return px - r >= 0 && px + r <= trip.width - 1 && py - r >= 0 && py + r <= trip.height - 1;
  };
  for (size_t k = 0; k < tracks.frames.size(); ++k) {
    const long fk = tracks.frames[k].number;
    if (fk < 0 || fk >= truth.size()) continue;
    const core::Frame g = truth.frame(fk);
    row.arch_frames_true += g.clog_open && !g.arch.empty();
    row.arch_frames_found += trip.im.frames[k].clog_open && !trip.im.frames[k].arch.empty();
    const auto& found = tracks.frames[k].found;
    std::vector<std::pair<double, std::pair<size_t, int>>> pairs;
    for (size_t a = 0; a < found.size(); ++a)
      for (size_t b = 0; b < g.particles.size(); ++b) {
        const core::Particle& p = g.particles[b];
        const double d = std::hypot(found[a].x - p.x, found[a].y - p.y);
        if (d < 0.5 * p.radius) pairs.push_back({d, {a, static_cast<int>(b)}});
      }
    std::sort(pairs.begin(), pairs.end());
    std::vector<bool> det_used(found.size(), false), true_used(g.particles.size(), false);
    for (const auto& [d, ab] : pairs) {
      if (det_used[ab.first] || true_used[static_cast<size_t>(ab.second)]) continue;
      det_used[ab.first] = true_used[static_cast<size_t>(ab.second)] = true;
      trip.truth_of[k][found[ab.first].id] = ab.second;
    }
    for (size_t b = 0; b < g.particles.size(); ++b)
      if (whole_in_view(g.particles[b])) (true_used[b] ? tp : fn) += 1;
    for (size_t a = 0; a < found.size(); ++a)
      if (!det_used[a]) ++fp;
    for (const auto& [id, b] : trip.truth_of[k]) {
      const core::Particle& p = g.particles[static_cast<size_t>(b)];
      for (const auto& f : found)
        if (f.id == id) errors.push_back(std::hypot(f.x - p.x, f.y - p.y) / (2 * p.radius));
      ++grain_frames;
      // A switch: the same grain under another id, from one frame to the next, without having left.
      auto it = last_track.find(b);
      if (it != last_track.end() && it->second != id && k > 0 && trip.truth_of[k - 1].count(it->second) &&
          trip.truth_of[k - 1].at(it->second) == b)
        ++row.id_switches;
      last_track[b] = id;
    }
  }
  row.recall = tp + fn > 0 ? static_cast<double>(tp) / static_cast<double>(tp + fn) : NAN;
  row.precision = tp + fp > 0 ? static_cast<double>(tp) / static_cast<double>(tp + fp) : NAN;
  row.error_median_d = core::median(errors);
  row.error_p95_d = quantile_of(errors, 0.95);
  row.switches_per_1000 =
      grain_frames > 0 ? 1000.0 * static_cast<double>(row.id_switches) / grain_frames : NAN;
}

// The arch the import holds for found clog `best`, against the recording's arch at the same frame: member
// recall and precision, descriptor errors.
struct ArchScore {
  long members_true = 0, members_found = 0, members_both = 0;
  std::vector<double> span_err, rise_err, theta_err;
};
void score_arch(const io::Trajectory& truth, const Trip& trip, size_t best, ArchScore& sc,
                RoundTripRow& row) {
  for (const lab::ClogArch& a : trip.im.clog_arches) {
    if (a.clog != static_cast<int>(best) + 1) continue;
    size_t k = 0;
    while (k + 1 < trip.im.frames.size() && trip.im.frames[k].t < a.t - 1e-9) ++k;
    const core::Frame g = truth.frame(trip.tracks.frames[k].number);
    if (g.arch.empty()) return;
    std::set<int> truth_members(g.arch.begin(), g.arch.end()), found_members;
    for (long track : a.track_ids) {
      auto it = trip.truth_of[k].find(track);
      if (it != trip.truth_of[k].end()) found_members.insert(it->second);
    }
    sc.members_true += static_cast<long>(truth_members.size());
    sc.members_found += static_cast<long>(a.track_ids.size());
    for (int m : found_members) sc.members_both += truth_members.count(m);
    std::vector<core::Vec2> pos;
    std::vector<double> radius;
    for (const core::Particle& p : g.particles) pos.push_back({p.x, p.y}), radius.push_back(p.radius);
    const core::ArchDescriptors dt = core::arch_descriptors(g.arch, pos, radius);
    const double d = 2 * trip.model.setup.reference_radius;
    sc.span_err.push_back(std::fabs(a.descriptors.span - dt.span) / d);
    sc.rise_err.push_back(std::fabs(a.descriptors.rise - dt.rise) / d);
    sc.theta_err.push_back(std::fabs(a.descriptors.theta_max_deg - dt.theta_max_deg));
    ++row.arches_compared;
    return;
  }
}

// Clogs: each true clog matched to the found clog whose start is nearest, within 0.25 s, and its arch; the
// exits per species.
void score_clogs(const io::Trajectory& truth, const Trip& trip, RoundTripRow& row) {
  const auto& tc = truth.events().clogs;
  const auto& fc = trip.im.events.clogs;
  row.true_clogs = static_cast<long>(tc.size());
  row.found_clogs = static_cast<long>(fc.size());
  std::vector<double> dstart, dend;
  ArchScore sc;
  std::set<size_t> used;
  for (const core::ClogEvent& c : tc) {
    size_t best = fc.size();
    double bd = 0.25;
    for (size_t j = 0; j < fc.size(); ++j)
      if (!used.count(j) && std::fabs(fc[j].start - c.start) <= bd)
        bd = std::fabs(fc[j].start - c.start), best = j;
    if (best == fc.size()) continue;
    used.insert(best);
    ++row.matched_clogs;
    row.arrested_agree += fc[best].arrested == c.arrested;
    dstart.push_back(std::fabs(fc[best].start - c.start));
    dend.push_back(std::fabs(fc[best].end - c.end));
    score_arch(truth, trip, best, sc, row);
  }
  // Exits until three frames before the film's last, both ways: a grain last seen near the outlet in the last
  // frames may leave after the film ends (the recording has its exit, the film none), or be counted as gone
  // at the last frame before the recording's exit line.
  const auto& frames = trip.im.frames;
  const double until =
      frames.size() < 5 ? -INFINITY : frames.back().t - 3 * (frames.back().t - frames[frames.size() - 2].t);
  auto per_species = [&](const std::vector<core::ExitEvent>& exits, std::vector<long>& out) {
    for (const core::ExitEvent& e : exits) {
      if (e.t > until + 1e-9) continue;
      const size_t k = static_cast<size_t>(core::species_index(e.species));
      if (out.size() <= k) out.resize(k + 1, 0);
      ++out[k];
    }
  };
  per_species(truth.events().exits, row.true_exits);
  per_species(trip.im.events.exits, row.found_exits);
  row.start_error_s = core::median(dstart);
  row.end_error_s = core::median(dend);
  row.member_recall = sc.members_true > 0 ? static_cast<double>(sc.members_both) / sc.members_true : NAN;
  row.member_precision = sc.members_found > 0 ? static_cast<double>(sc.members_both) / sc.members_found : NAN;
  row.span_error_d = core::median(sc.span_err);
  row.rise_error_d = core::median(sc.rise_err);
  row.theta_error_deg = core::median(sc.theta_err);
}

}  // namespace

RoundTripRow round_trip(const fs::path& recording, double level, double drop, std::uint64_t seed,
                        const fs::path& tracks_csv, double contact_tolerance, bool reuse_tracks) {
  const io::Run run = io::Run::open(recording, "bench roundtrip", io::Run::kTrajectory);
  const io::Trajectory& truth = run.trajectory();
  const auto movie_name = run.metadata()["run"]["movie"].value<std::string>();
  if (!movie_name) throw core::InputError(recording.string() + ": not a recording (no [run] movie)");
  const fs::path movie = recording.parent_path() / *movie_name;
  Trip trip;
  std::string why;
  if (!movie_calibration(movie, trip.cal, trip.model, why))
    throw core::InputError(movie.string() + ": cannot serve as ground truth: " + why);
  {
    vision::FrameSource probe(movie.string());
    trip.width = probe.width(), trip.height = probe.height();
  }
  // The movie through the camera's noise and losses, detected, then imported.
  DetectJob job;
  job.cal = trip.cal;
  for (const core::SpeciesDef& sp : trip.model.setup.species)
    job.detect.radius_px.push_back(sp.radius / trip.cal.scale);
  job.camera = [level, seed](const cv::Mat& clean, long k) {
    return vision::add_camera(clean, level, seed * 1000003ULL + static_cast<std::uint64_t>(k));
  };
  job.drop = drop;
  job.seed = seed;
  DetectStats st;
  if (!reuse_tracks || !fs::exists(tracks_csv)) {
    vision::FrameSource source(movie.string());
    io::write_file_atomic(tracks_csv, detect_tracks(source, job, trip.model, st), false);
  } else {
    st.seconds = NAN;
  }
  lab::Units units;
  units.scale = trip.cal.scale;
  units.origin_x = trip.cal.origin_x;
  units.origin_y = trip.cal.origin_y;
  units.rotation = trip.cal.rotation;
  trip.tracks = lab::read_tracks(tracks_csv.string(), {}, units, trip.model.setup, trip.model.setup.geo);
  lab::ImportOptions opt;
  opt.contact_tolerance = contact_tolerance;
  trip.im = lab::import_tracks(trip.tracks, trip.model, opt);

  RoundTripRow row;
  row.level = level;
  row.drop = drop;
  row.frames = static_cast<long>(trip.tracks.frames.size());
  row.detect_s_per_frame = st.seconds / std::max(1L, st.frames);
  row.contact_tolerance = contact_tolerance;
  row.frames_clogged = trip.im.report.frames_clogged;
  row.clogged_with_arch = trip.im.report.frames_clogged_with_arch;
  row.flowing_with_arch = trip.im.report.frames_flowing_with_arch;
  score_grains(truth, trip, row);
  score_clogs(truth, trip, row);
  return row;
}

}  // namespace app
