#include "app/services/accuracy.h"

#include "app/services/session.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <mutex>
#include <thread>

#include "core/physics.h"
#include "sim/dipole.h"
#include "sim/silo.h"

namespace app {

void NumericSetting::apply(core::Scene& s) const {
  s.dt = dt;
  s.velocity_iterations = velocity_iterations;
  s.position_iterations = position_iterations;
  s.length_scale = length_scale;
  s.continuous = continuous;
  s.arrest_skip = arrest_skip;
  s.arrest_skip_shift = arrest_skip_shift;
  s.dipole_cutoff = 0;
  if (dipole_cutoff_fraction > 0 && s.mu > 0) {
    // The distance at which the pair force falls to this fraction of an added disk's weight.
    const double w = core::mass_of(s.radius_added(), s.density) * s.gravity;
    s.dipole_cutoff = std::pow(core::kDipolePrefactor * s.mu * s.mu / (dipole_cutoff_fraction * w), 0.25);
  }
}

namespace {
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

SettingResult run_setting(const core::Scene& scene, const NumericSetting& setting, int realizations,
                          int threads) {
  SettingResult out;
  std::mutex m;
  std::atomic<int> next{1};
  double overlap_sum = 0;
  long overlap_n = 0;
  auto worker = [&] {
    for (int seed; (seed = next++) <= realizations;) {
      core::Scene s = scene;
      setting.apply(s);
      s.seed = static_cast<std::uint64_t>(seed);
      try {
        Session session({core::compile(s)});
        const sim::Silo& h = session.world(0);
        // The discharge's CPU time on this thread (one world steps on the caller's thread), not wall time:
        // on a shared machine other work stretches wall time unevenly between settings, and the ratios
        // between them are what the table is for.
        const double c0 = thread_cpu_seconds();
        session.run(s.duration, FrameClock::none(), {});
        session.finish();
        const double cpu = thread_cpu_seconds() - c0;
        std::lock_guard lock(m);
        out.sim_seconds += s.duration;
        out.cpu_seconds += cpu;
        out.runs.push_back(analysis::measure(h.events(), s.duration, s.clog_min_gap));
        auto av = analysis::avalanche_sizes(h.events().exits, s.clog_min_gap);
        out.avalanche_sizes.insert(out.avalanche_sizes.end(), av.begin(), av.end());
        auto gaps = analysis::original_gaps(h.events().exits);
        out.original_gaps.insert(out.original_gaps.end(), gaps.begin(), gaps.end());
        for (const auto& c : h.events().clogs) {
          if (c.ended_by == core::ClogEnd::RunEnd) continue;
          out.clog_durations.push_back(c.end - c.start);
          ++out.clogs_ended;
          out.clogs_vibration += c.ended_by == core::ClogEnd::Vibration;
        }
        out.skipped_seconds += h.skipped_seconds();
        overlap_sum += h.overlaps().sum;
        overlap_n += h.overlaps().samples;
        out.overlap_max = std::max(out.overlap_max, h.overlaps().max);
      } catch (const std::exception& e) {
        std::lock_guard lock(m);
        if (out.failures++ == 0) out.failure = e.what();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < std::max(1, threads); ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  out.overlap_mean = overlap_n ? overlap_sum / overlap_n : 0;
  return out;
}

double pair_energy_drift(const core::Scene& scene, const NumericSetting& setting, double seconds) {
  core::Scene s = scene;
  setting.apply(s);
  s.n_total = 2;
  s.chi = 1.0;
  s.gravity = 0;
  s.kick_impulse_max = 0;
  s.settle_time = 0;
  s.dipole_cutoff = 0;
  Session session({core::compile(s)});
  sim::Silo& h = session.world(0);
  // Start one contact-gap apart in the middle of the silo, at rest: all energy is the dipole's at first.
  const double ra = s.radius_added(), y = 3.0;
  h.place(0, {-ra - 0.25 * ra, y});
  h.place(1, {ra + 0.25 * ra, y});
  auto energy = [&] {
    core::Frame f = h.frame(false);
    const double m = core::mass_of(ra, s.density);
    double e = 0;
    for (const auto& p : f.particles) e += 0.5 * m * (p.vx * p.vx + p.vy * p.vy);
    return e +
           sim::dipole_energy(
               std::hypot(f.particles[0].x - f.particles[1].x, f.particles[0].y - f.particles[1].y), s.mu);
  };
  const double e0 = energy();
  // Stop before either disk comes within two radii of a side wall: wall contacts are inelastic by design.
  const double limit = h.geometry().half_width - 3 * ra;
  FunctionSink probe;
  probe.on_step = [&](const sim::Silo& w, const core::StepEvents&, size_t) {
    const auto p = w.positions();
    return std::abs(p[0].x) <= limit && std::abs(p[1].x) <= limit;
  };
  session.run(seconds, FrameClock::none(), {&probe});
  return std::abs(energy() - e0) / e0;
}

}  // namespace app
