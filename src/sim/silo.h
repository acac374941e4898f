// A two-dimensional silo in Box2D 2.4: the vibrated hopper of Carlevaro et al. (2022) and any other clogging
// experiment a scene describes (core/setup.h: species of disks or polygons, a hopper or a flat floor, an
// obstacle, a tilt, kicks and/or a harmonically vibrated container).
//
// Construction deposits the grains at random with the aperture closed, lets them settle for settle_time and
// opens the aperture: time() is 0 afterwards. Each step() applies the kicks (when due), moves a vibrating
// container, applies the dipole forces, steps Box2D by dt, re-injects the grains that fell through the
// aperture (one exit event each) and applies the clog_timeout rule. A scene pays only for what it uses: no
// dipole work without dipoles, circles without polygons, a static container without vibration. Everything is
// SI outside this class; inside, Box2D runs with lengths multiplied by scene.length_scale so its absolute
// tolerances (linear slop 0.005) suit grains of a few centimetres. Positions used for the rules (exits,
// arches, re-injection, health) are in the container's frame; Frames carry world positions and the
// container's displacement.
#pragma once

#include <chrono>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/arch.h"
#include "core/clog.h"
#include "core/events.h"
#include "core/frame.h"
#include "core/geometry.h"
#include "core/model.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/setup.h"
#include "sim/dipole.h"

class b2World;
class b2Body;
class b2Fixture;
class b2Contact;

namespace sim {

// Cumulative wall time of each stage of step(), filled when profiling is on.
struct StageTimes {
  double kicks = 0, dipoles = 0, box2d = 0, bookkeeping = 0;  // s
  // Inside Box2D's step (its own b2Profile): finding contacts (broad phase and narrow phase), the contact
  // solver (initialisation, velocity and position iterations, integration), continuous collision.
  double contacts = 0, solver = 0, toi = 0;  // s
  long steps = 0;
};

class Silo {
 public:
  // The scene compiled once (core/model.h); the simulation keeps its own copy.
  explicit Silo(const core::Model& model);
  ~Silo();
  Silo(const Silo&) = delete;
  Silo& operator=(const Silo&) = delete;

  // One time step; returns what it did (exits, a clog opened or closed, the rule's removal, the time until
  // the rule is due). The report is also kept until take_events() collects it.
  const core::StepEvents& step();
  // Everything reported since the last call (merged), and the state after the last step.
  core::StepEvents take_events();
  // The open clog (none while settling): its row of clogs.csv, start, arrest and arch.
  const core::ClogState& clog() const { return clogs_.state(); }
  // Step until time() >= t (to within a hundredth of a step).
  void advance_to(double t);
  double time() const { return t_; }
  std::uint64_t steps() const { return step_; }

  // The snapshot the renderer and trajectory see, with the open clog and its arch as the steps reported them
  // (no detection here). Work nobody will look at is skipped: with_forces sums contact impulses into
  // per-disk forces and lists the contacts (needed to colour by force or draw chains).
  core::Frame frame(bool with_forces = true) const;
  // Forces in frames averaged over the steps since restart_force_average() (a frame interval), not the last
  // step's alone: a contact that touches at the frame gets its impulses' mean over the window, the steps it
  // did not touch counted as 0 (a kick's spike is spread over the frame as the solver spread it over time).
  // Off by default (frames then hold the last step's); a run that records contacts turns it on.
  void average_forces(bool on);
  bool averaging_forces() const { return averaging_; }
  void restart_force_average();
  // The arch Box2D's contacts hold now, left to right (empty when none): what the rule removes. Pictures
  // show the open clog's arch instead (clog().arch).
  std::vector<int> current_arch() const;
  core::ContactGraph contact_graph() const;
  // Every touching contact's force as the last step's solver applied it (normal and tangential impulses over
  // dt; grain-grain and grain-wall, the wall first), N, world frame (silo_forces.cpp).
  std::vector<core::ContactForce> contact_forces() const;
  // Each grain's weight, mass times gravity, N.
  std::vector<core::Vec2> weights() const;
  // The arch's load, its walls' reaction, its weight and its imbalance, into the event (silo_forces.cpp).
  void record_arch_forces(core::ArchEvent& ev) const;

  // Events so far; finish() closes an open clog as censored (call once at the end of a run) and reports it.
  const core::Events& events() const { return events_; }
  const core::StepEvents& finish();

  const core::Scene& scene() const { return model_.scene; }
  const core::Setup& setup() const { return model_.setup; }
  const core::Model& model() const { return model_; }
  const core::Geometry& geometry() const { return geo_; }
  int particle_count() const { return static_cast<int>(bodies_.size()); }
  // Centres in the container's frame, m.
  std::vector<core::Vec2> positions() const;
  // Radii of the disks of equal area, m (a disk's own radius).
  std::vector<double> radii() const { return radius_; }
  const std::vector<core::Species>& species() const { return species_; }
  // Sides of each grain: 0 for a disk, 3-8 for a regular polygon.
  const std::vector<std::uint8_t>& sides() const { return sides_; }
  // The container's displacement now (a vibrating container), m.
  core::Vec2 container_offset() const { return offset_; }

  // The arrested-state shortcut (scene.arrest_skip): how many clogs it jumped to the rule, and the simulated
  // seconds it did not integrate.
  long arrest_skips() const { return arrest_skips_; }
  double skipped_seconds() const { return skipped_s_; }

  // The drain protocol (scene.drain): grains still in the container, and how the drain ended: "draining"
  // (neither yet), "emptied" (the last grain left at end_s) or "jammed" (at end_s a clog had lasted
  // clog_timeout; from then on nothing moves and the steps integrate nothing).
  struct Drain {
    int remaining = 0;
    std::string outcome = "draining";
    double end_s = NAN;
  };
  const Drain& drain() const { return drain_; }

  // The direction the exiting grains move as they cross the outlet's line (their centre passing it), in the
  // container's frame: the angle of each one's velocity from the outlet's outward normal (positive towards
  // +x), deg. Thomas and Durian project the outlet across this direction, not across gravity.
  struct ExitDirection {
    long exits = 0;                        // exits whose crossing was seen
    double sum_vx = 0, sum_vy = 0;         // their crossing velocities, m/s
    double sum_angle = 0, sum_angle2 = 0;  // their angles, rad
    double mean_velocity_deg() const;      // the direction of their mean velocity
    double angle_sd_deg() const;           // the spread of their angles
  };
  const ExitDirection& exit_direction() const { return exit_direction_; }
  bool drained_out() const { return drain_.outcome != "draining"; }

  // Number of arch fallbacks (the primary arch method found nothing when the rule fired).
  long arch_fallbacks() const { return arch_fallbacks_; }
  // Settling outcome: the largest disk speed (m/s) when the aperture opened.
  double settle_max_speed() const { return settle_max_speed_; }

  // Overlaps between touching disks, as a fraction of the smaller radius of each pair, sampled at every kick
  // after the opening: the mean over all sampled contacts and the largest seen.
  struct OverlapStats {
    double sum = 0, max = 0;
    long samples = 0;
    double mean() const { return samples ? sum / samples : 0.0; }
  };
  const OverlapStats& overlaps() const { return overlaps_; }
  // Disks in flight: the fraction whose lower edge is more than two original diameters above the column top,
  // sampled at every kick after the opening (mean and largest). A mean above kBallisticFraction is the named
  // health warning "ballistic": the kicks throw disks about, and the flow is no longer a dense granular flow.
  struct Airborne {
    double sum = 0, max = 0;
    long samples = 0;
    double mean() const { return samples ? sum / samples : 0.0; }
  };
  static constexpr double kBallisticFraction = 0.01;
  // Scenes of more grains than this make their Box2D bodies in order of height (memory follows space).
  static constexpr int kSpatialOrderAbove = 1000;
  const Airborne& airborne() const { return airborne_; }
  bool ballistic() const { return airborne_.mean() > kBallisticFraction; }
  // The top of the packed column, m: the top edge of the highest horizontal slab (one original diameter
  // thick) that disks cover by at least 35%; disks in flight above it do not count. In a tilted container
  // the slabs lie across gravity and the height is up_height's.
  double column_top(int except = -1) const;
  // Height along gravity's up direction in the container's frame, m (y when the container stands upright).
  double up_height(core::Vec2 p) const;
  // With scene.unsafe, health problems are warned about (the first few printed) and counted instead of
  // stopping.
  long health_warnings() const { return health_warnings_; }

  void set_profiling(bool on) { profiling_ = on; }
  // Box2D's contacts now: pairs whose bounding boxes overlap, and those of them touching.
  long contacts(bool touching_only) const;
  const StageTimes& stage_times() const { return times_; }

  // The benchmark's baseline: n steps of the Box2D world alone (no kicks, dipoles or bookkeeping; time does
  // not advance). Box2D stays inside sim: nothing above it needs its types.
  void step_box2d_only(int n);
  // Move disk `id` to p (m) at rest; tests use it to build arches by hand.
  void place(int id, core::Vec2 p);
  void set_velocity(int id, core::Vec2 v);  // m/s
  // Change the kick strength from now on (N*s); tests stage a clog without kicks, then kick it.
  // The simulation reads the kicks from the setup's drive only (scene() keeps the scene as written).
  void set_kick_impulse_max(double j) {
    model_.setup.drive.kick_impulse_max = j;
    clogs_.set_driven(j > 0 || model_.setup.drive.vibrating());
  }
  // Switch the clog_timeout rule off from now on (or back on at the scene's timeout): the break test
  // (sim/breaking.h) keeps an arch as long as it stands.
  void set_clog_rule(bool on) { clogs_.set_timeout(on ? scene_.clog_timeout : 0); }
  // Every grain's velocity changed at once (the break test's kick, silo_forces.cpp): by dv along gravity's up
  // direction (m/s; the container dropped away from under the packing), or, `random`, by the scene's kick law
  // as velocities (each grain its own change, direction uniform, size uniform in [0, dv], plus one shared
  // change of the same law) drawn from `seed`: the same draws scaled for every dv.
  void kick_all(double dv, bool random = false, std::uint64_t seed = 0);
  // Grains taken out by hand ("what if"), between steps: each re-injected above the column as the clog rule
  // does. While a clog is open it ends now as by the rule, the removed grains its row of arches.csv; while
  // flowing nothing is recorded. Returns what it reported. Throws core::InputError for an id not in the
  // container.
  const core::StepEvents& remove_by_hand(const std::vector<int>& ids);
  // Every grain of species `species` (its index) given dipole moment `moment` (A*m^2; 0: none) from now on
  // ("what if"; the scene keeps the moment it was written with).
  void set_dipole(int species, double moment);
  // Close the outlet (the lid the deposition stood on, back across the aperture) or open it again, from the
  // next step; for protocols of one's own (the Python bindings). While it is closed no grain exits, so the
  // clog tracker sees a gap like any other.
  void set_outlet_open(bool open);
  bool outlet_open() const { return lid_ == nullptr; }
  // Run every health check now (they also run on their own: per disk every step, overlaps at every kick).
  void check_health();

 private:
  void build_walls();
  b2Fixture* add_wall(int wall);
  double deposit_height() const;
  void make_grains();
  void deposit();
  void settle();
  void open_aperture();
  void apply_kicks();
  void apply_dipoles();
  void drive_container();
  void add_grain(int id, core::Vec2 p, double angle);
  double draw_radius(const core::SpeciesDef& d);
  void integrate_step();
  void handle_exits();
  void apply_clog_rule();
  // The arch event `ev` (time, clog duration, method, ids) completed from positions `p` and the forces, its
  // grains re-injected, recorded, and the open clog closed by the rule.
  void remove_arch(core::ArchEvent ev, const std::vector<core::Vec2>& p);
  void record_closed_clogs();
  // The arch Box2D's contacts hold now if it blocks the outlet (core::blocks_outlet), else empty.
  std::vector<int> blocking_arch() const;
  // Whether each member of `arch` touches the next (an arch is a chain of touching grains; two neighbours
  // that both rest on the obstacle are linked by it, as the arch detection links them).
  bool chain_touches(const std::vector<int>& arch) const;
  // The gap between grain i's shape and a fixture's (Box2D units; 0 when they overlap).
  double gap_to(int i, const b2Fixture* other) const;
  // Neighbours of an arch touch when their shapes are at most this fraction of the smaller radius apart.
  static constexpr double kArchContactGap = 0.05;
  void check_health_fast(int id, core::Vec2 p, core::Vec2 v) const;
  void check_overlaps();
  bool outlet_arrested(const std::vector<int>& arch) const;
  bool still_since_last_kick();
  void start_skip();
  void skipped_step(bool kick_due);
  void accumulate_impulses();
  // The averaged normal and tangential impulse of contact (a, b) (decoded fixtures), in Box2D's units; the
  // last step's when not averaging.
  struct Impulses {
    double normal = 0, tangent = 0;
  };
  Impulses impulses(const b2Contact* c, int a, int b) const;
  bool averaging_ = false;
  long averaged_steps_ = 0;
  std::unordered_map<std::uint64_t, Impulses> impulse_sums_;
  void sample_airborne();
  void reinject(int id);
  void park(int id);  // drain: an exit leaves the world (disabled, 2 H + 1 m below the outlet)
  void reinject_tilted(int id);
  bool free_at(core::Vec2 p,
               int id) const;           // grain id fits at p (clear of the obstacle and every other grain)
  void put_back(int id, core::Vec2 p);  // re-injected at p, at rest (a polygon at a random orientation)
  [[noreturn]] void no_room_to_reinject(int id) const;
  // A tilted container cut across gravity into slabs one diameter thick: the height h (up_height) of each
  // slab's bottom, and where a line across gravity through its middle enters and leaves the container
  // (coordinates along the across direction (up.y, -up.x)).
  struct Level {
    double h, s_min, s_max;
  };
  const std::vector<Level>& levels() const;
  double column_top_tilted(int except) const;
  // Settling in a tilted container: filled upright, then turned to its tilt with the outlet closed.
  void settle_tilted();
  core::Vec2 pos(int id) const;
  core::Vec2 vel(int id) const;

  core::Model model_;  // the one copy: the scene as written and what it resolved to
  const core::Scene& scene_ = model_.scene;
  const core::Setup& setup_ = model_.setup;
  core::Geometry geo_;
  double L_;                   // Box2D length units per metre
  double deposit_height_ = 0;  // m, top of the deposition column
  std::unique_ptr<b2World> world_;
  b2Body* walls_ = nullptr;
  b2Fixture* lid_ = nullptr;
  b2Fixture* ceiling_ = nullptr;         // closes the deposition column while settling
  const b2Fixture* obstacle_ = nullptr;  // the obstacle above the outlet, if the scene has one
  std::vector<b2Body*> bodies_;
  std::vector<double> radius_;  // equal-area radius
  std::vector<double> extent_;  // circumradius (= radius_ for disks): the reach of a grain
  std::vector<std::uint8_t> sides_;
  std::vector<double> angle_;  // initial orientations, between make_grains() and deposit()
  std::vector<core::Species> species_;
  std::vector<int> dipole_ids_;        // grains with a dipole moment, in id order
  std::vector<double> dipole_moment_;  // their moments, A*m^2
  DipoleCells dipole_cells_;
  core::Rng rng_deposit_, rng_kick_, rng_reinject_, rng_shape_, rng_orient_;
  std::vector<core::Vec2> scratch_pos_, scratch_force_, scratch_kick_;
  core::Vec2 offset_;    // the container's displacement, m
  core::Vec2 up_{0, 1};  // against gravity, in the container's frame (unit)
  mutable std::vector<Level> levels_;

  double t_ = 0;
  std::uint64_t step_ = 0;
  std::uint64_t open_step_ = 0;  // step index of t = 0
  std::uint64_t kick_every_ = 1;
  bool open_ = false;
  core::ClogTracker clogs_;
  core::Events events_;
  core::StepEvents last_;     // what the current (or last) step did
  core::StepEvents pending_;  // what the steps did since take_events()
  long arch_fallbacks_ = 0;
  core::ArchMethod arch_method_ = core::ArchMethod::ContactPath;  // scene_.arch_method, parsed once
  std::vector<std::int64_t> exits_by_species_;                    // exits so far of each species
  double settle_max_speed_ = 0;
  bool profiling_ = false;
  OverlapStats overlaps_;
  Airborne airborne_;
  ExitDirection exit_direction_;
  std::vector<core::Vec2> crossing_v_;  // each grain's velocity as its centre crossed the outlet's line
  std::vector<char> crossed_;           // whether it has crossed since it was (re)placed
  std::uint64_t hold_steps_ = 1;        // arrest_hold in steps
  std::vector<core::Vec2> hold_pos_;    // positions arrest_hold before the coming kick
  std::vector<core::Vec2> kick_pos_;    // positions at the last kick (the shortcut's stillness test)
  Drain drain_;
  std::vector<char> parked_;      // drain: grains that left (empty otherwise)
  std::uint64_t skip_until_ = 0;  // the shortcut: steps before this one are not integrated
  long still_kicks_ = 0;          // consecutive kicks at which the outlet was arrested and all was still
  long arrest_skips_ = 0;
  double skipped_s_ = 0;
  mutable long health_warnings_ = 0;
  void warn_unsafe(const std::string& msg) const;
  StageTimes times_;
};

}  // namespace sim
