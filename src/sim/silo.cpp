// sim::Silo: the Box2D world of one scene (walls, grains, deposition, kicks, vibration, dipoles) and its
// step. Over 400 lines because the step's parts share the b2World's state; its health checks are in
// silo_health.cpp, filling in silo_fill.cpp, arches in silo_arches.cpp, contact forces in silo_forces.cpp,
// the dipole forces in dipole.cpp, changes by hand ("what if") in silo_whatif.cpp.
#include "sim/silo.h"
#include "core/format.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "core/physics.h"
#include "core/portable_math.h"
#include "sim/dipole.h"
#include "sim/kicks.h"
#include "sim/silo_internal.h"

// The metadata states the contact slop as 0.005 Box2D units (io/metadata.cpp); fail the build if this Box2D
// differs.
static_assert(b2_linearSlop == 0.005f && b2_lengthUnitsPerMeter == 1.0f,
              "Box2D's linear slop changed: update box2d_linear_slop_m in io/metadata.cpp");

namespace sim {

namespace {
using internal::decode;
using internal::fmt4;
using internal::kWallTag;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
}  // namespace

Silo::Silo(const core::Model& model)
    : model_(model),
      geo_(setup_.geo),
      L_(scene_.length_scale),
      rng_deposit_(scene_.seed, 1),
      rng_kick_(scene_.seed, 2),
      rng_reinject_(scene_.seed, 3),
      rng_shape_(scene_.seed, 4),
      rng_orient_(scene_.seed, 5),
      clogs_(scene_.clog_min_gap, scene_.clog_timeout,
             setup_.drive.kick_impulse_max > 0 || setup_.drive.vibrating()) {
  arch_method_ = setup_.arch_method;
  // Time steps the integration cannot survive are refused before any work: the explicit dipole repulsion,
  // and grains outrunning their own size in one step.
  const double dipole_dt = core::dipole_safe_dt(setup_),
               kinematic_dt = core::kinematic_safe_dt(setup_, scene_.gravity);
  std::string refusal;
  if (scene_.dt > dipole_dt)
    refusal = "dt = " + fmt4(scene_.dt) + " s is too large for the dipole repulsion " +
              (setup_.shorthand ? "at mu = " + fmt4(scene_.mu) + " A*m^2 and r = " + fmt4(scene_.size_ratio)
                                : std::string("between the smallest grains that carry dipoles")) +
              "; the largest safe time step is " + fmt4(std::min(dipole_dt, kinematic_dt)) + " s";
  else if (scene_.dt > kinematic_dt)
    refusal = "dt = " + fmt4(scene_.dt) +
              " s lets a falling disk move more than the smallest diameter per step " +
              "(free fall from the top); the largest safe time step is " + fmt4(kinematic_dt) + " s";
  if (!refusal.empty()) {
    if (!scene_.unsafe) throw core::InputError("scene: " + refusal + " (or pass --unsafe)");
    warn_unsafe(refusal);
  }
  kick_every_ = static_cast<std::uint64_t>(std::llround(scene_.kick_period / scene_.dt));
  open_step_ = static_cast<std::uint64_t>(std::llround(scene_.settle_time / scene_.dt));
  hold_steps_ = static_cast<std::uint64_t>(std::llround(scene_.arrest_hold / scene_.dt));
  if (setup_.tilt != 0) core::portable::sincos(setup_.tilt, up_.x, up_.y);  // gravity along -up_

  world_ = std::make_unique<b2World>(
      b2Vec2(static_cast<float>(setup_.gravity.x * L_), static_cast<float>(setup_.gravity.y * L_)));
  world_->SetAllowSleeping(false);  // sleeping would freeze clogged arches between kicks
  world_->SetContinuousPhysics(scene_.continuous);
  exits_by_species_.assign(setup_.species.size(), 0);
  make_grains();
  if (scene_.drain) parked_.assign(static_cast<size_t>(setup_.n_total), 0), drain_.remaining = setup_.n_total;
  deposit_height_ = deposit_height();
  build_walls();
  deposit();
  settle();
  open_aperture();
}

Silo::~Silo() = default;

void Silo::build_walls() {
  b2BodyDef def;
  // A vibrating container is a kinematic body that the drive moves; otherwise a static one (a kinematic body
  // would merge every grain touching it into one island and change the solver's order).
  if (setup_.drive.vibrating()) def.type = b2_kinematicBody;
  walls_ = world_->CreateBody(&def);
  for (int w = 0; w < static_cast<int>(core::Wall::Count); ++w) {
    if (w != static_cast<int>(core::Wall::Top) && w != static_cast<int>(core::Wall::Obstacle)) add_wall(w);
  }
  if (geo_.obstacle.present()) {
    const core::Obstacle& ob = geo_.obstacle;
    b2FixtureDef fd;
    b2CircleShape circle;
    b2PolygonShape box;
    if (ob.kind == core::Obstacle::Kind::Disk) {
      circle.m_radius = static_cast<float>(0.5 * ob.width * L_);
      circle.m_p.Set(static_cast<float>(ob.centre.x * L_), static_cast<float>(ob.centre.y * L_));
      fd.shape = &circle;
    } else {
      box.SetAsBox(static_cast<float>(0.5 * ob.width * L_), static_cast<float>(0.5 * ob.height * L_),
                   b2Vec2(static_cast<float>(ob.centre.x * L_), static_cast<float>(ob.centre.y * L_)), 0.0f);
      fd.shape = &box;
    }
    fd.friction = static_cast<float>(scene_.friction);
    fd.restitution = static_cast<float>(scene_.restitution);
    fd.restitutionThreshold = static_cast<float>(scene_.restitution_threshold * L_);
    fd.userData.pointer = kWallTag + static_cast<std::uintptr_t>(core::Wall::Obstacle);
    obstacle_ = walls_->CreateFixture(&fd);
  }
  // While settling, a ceiling closes the deposition column: strong dipoles can throw grains upwards.
  b2EdgeShape edge;
  const float y = static_cast<float>(deposit_height_ * L_);
  edge.SetTwoSided(b2Vec2(static_cast<float>(geo_.x_left * L_), y),
                   b2Vec2(static_cast<float>(geo_.x_right * L_), y));
  b2FixtureDef fd;
  fd.shape = &edge;
  fd.friction = static_cast<float>(scene_.friction);
  fd.userData.pointer = kWallTag + static_cast<std::uintptr_t>(core::Wall::Count);
  ceiling_ = walls_->CreateFixture(&fd);
}

b2Fixture* Silo::add_wall(int w) {
  {
    core::Segment s = geo_.walls[w];
    if (w == static_cast<int>(core::Wall::SiloLeft)) s.a.y = deposit_height_;
    if (w == static_cast<int>(core::Wall::SiloRight)) s.b.y = deposit_height_;
    b2EdgeShape edge;
    edge.SetTwoSided(b2Vec2(static_cast<float>(s.a.x * L_), static_cast<float>(s.a.y * L_)),
                     b2Vec2(static_cast<float>(s.b.x * L_), static_cast<float>(s.b.y * L_)));
    b2FixtureDef fd;
    fd.shape = &edge;
    fd.friction = static_cast<float>(scene_.friction);
    fd.restitution = static_cast<float>(scene_.restitution);
    fd.restitutionThreshold = static_cast<float>(scene_.restitution_threshold * L_);
    fd.userData.pointer = kWallTag + static_cast<std::uintptr_t>(w);
    b2Fixture* f = walls_->CreateFixture(&fd);
    if (w == static_cast<int>(core::Wall::Lid)) lid_ = f;
    return f;
  }
}

core::Vec2 Silo::pos(int id) const {
  // In the container's frame (offset_ is zero unless it vibrates: x - 0 is x, bit for bit).
  const b2Vec2& p = bodies_[id]->GetPosition();
  return {p.x / L_ - offset_.x, p.y / L_ - offset_.y};
}
core::Vec2 Silo::vel(int id) const {
  const b2Vec2& v = bodies_[id]->GetLinearVelocity();
  return {v.x / L_, v.y / L_};
}
std::vector<core::Vec2> Silo::positions() const {
  std::vector<core::Vec2> out(bodies_.size());
  for (int i = 0; i < particle_count(); ++i) out[i] = pos(i);
  return out;
}

void Silo::place(int id, core::Vec2 p) {
  p = p + offset_;
  bodies_[id]->SetTransform(b2Vec2(static_cast<float>(p.x * L_), static_cast<float>(p.y * L_)), 0.0f);
  bodies_[id]->SetLinearVelocity(b2Vec2(0, 0));
  bodies_[id]->SetAngularVelocity(0);
}

void Silo::set_velocity(int id, core::Vec2 v) {
  bodies_[id]->SetLinearVelocity(b2Vec2(static_cast<float>(v.x * L_), static_cast<float>(v.y * L_)));
}

void Silo::apply_kicks() {
  draw_kicks(rng_kick_, setup_.drive.kick_impulse_max, setup_.drive.global_kick, particle_count(),
             scratch_kick_);
  for (int i = 0; i < particle_count(); ++i) {
    if (!parked_.empty() && parked_[static_cast<size_t>(i)]) continue;
    const core::Vec2& j = scratch_kick_[i];
    bodies_[i]->ApplyLinearImpulseToCenter(b2Vec2(static_cast<float>(j.x * L_), static_cast<float>(j.y * L_)),
                                           true);
  }
}

void Silo::apply_dipoles() {
  scratch_pos_.resize(dipole_ids_.size());
  for (size_t k = 0; k < dipole_ids_.size(); ++k) scratch_pos_[k] = pos(dipole_ids_[k]);
  dipole_forces(scratch_pos_, dipole_moment_, scene_.dipole_cutoff, scratch_force_, dipole_cells_);
  // Box2D clears forces after every step, so they are applied before each one.
  for (size_t k = 0; k < dipole_ids_.size(); ++k) {
    const core::Vec2& f = scratch_force_[k];
    bodies_[dipole_ids_[k]]->ApplyForceToCenter(
        b2Vec2(static_cast<float>(f.x * L_), static_cast<float>(f.y * L_)), true);
  }
}

void Silo::drive_container() {
  // The container follows A sin(omega t) exactly: each step it gets the velocity that takes it from where it
  // is to where it must be at the end of the step (so float rounding never accumulates).
  const core::Vec2 target = core::container_offset(setup_, t_ + scene_.dt);
  const b2Vec2& at = walls_->GetPosition();
  walls_->SetLinearVelocity(b2Vec2(static_cast<float>((target.x * L_ - at.x) / scene_.dt),
                                   static_cast<float>((target.y * L_ - at.y) / scene_.dt)));
}

const core::StepEvents& Silo::step() {
  last_.clear();
  integrate_step();
  if (averaging_) accumulate_impulses();
  last_.rule_due_in = open_ ? clogs_.rule_due_in(t_) : INFINITY;
  if (!last_.empty()) pending_.append(last_);
  pending_.rule_due_in = last_.rule_due_in;
  return last_;
}

core::StepEvents Silo::take_events() {
  core::StepEvents out = std::move(pending_);
  pending_.clear();
  pending_.rule_due_in = out.rule_due_in;
  return out;
}

void Silo::integrate_step() {
  Clock::time_point t0;
  if (profiling_) t0 = Clock::now();
  const std::int64_t every = static_cast<std::int64_t>(kick_every_);
  const std::int64_t phase =
      (((static_cast<std::int64_t>(step_) - static_cast<std::int64_t>(open_step_)) % every) + every) % every;
  const bool kick_due = phase == 0;
  if (skip_until_ > step_) return skipped_step(kick_due);
  if (drained_out()) {
    // The drain is over (emptied or jammed): time runs on to the run's end, nothing moves.
    ++step_;
    t_ = (static_cast<double>(step_) - static_cast<double>(open_step_)) * scene_.dt;
    return;
  }
  if (open_ && phase == every - static_cast<std::int64_t>(hold_steps_)) hold_pos_ = positions();
  if (kick_due) {
    if (open_) {
      // One arch detection per check: whether the outlet is arrested, and the open clog's arch.
      std::vector<int> arch = current_arch();
      const bool arrested = outlet_arrested(arch);
      // The arch drawn and counted is a chain of touching grains (the arrest above keeps its own rule): one
      // whose neighbours have come apart is no arch. A held arch is checked again in every frame (frame()):
      // hidden while a kick holds its grains apart, shown again when they touch, replaced by the next arch.
      if (!core::blocks_outlet(arch, positions(), radius_, geo_.half_aperture) || !chain_touches(arch))
        arch.clear();
      clogs_.on_rest_check(t_, arrested, arch);
      check_overlaps();
      sample_airborne();
      if (scene_.arrest_skip > 0) {
        still_kicks_ = arrested && still_since_last_kick() ? still_kicks_ + 1 : 0;
        if (still_kicks_ >= scene_.arrest_skip) start_skip();
      }
    }
    if (skip_until_ > step_) return skipped_step(kick_due);
    if (setup_.drive.kick_impulse_max > 0 && (open_ || setup_.drive.settle_kicks)) apply_kicks();
  }
  Clock::time_point t1;
  if (profiling_) t1 = Clock::now(), times_.kicks += std::chrono::duration<double>(t1 - t0).count();
  if (open_ && setup_.drive.vibrating()) drive_container();
  if (dipole_ids_.size() >= 2) apply_dipoles();
  Clock::time_point t2;
  if (profiling_) t2 = Clock::now(), times_.dipoles += std::chrono::duration<double>(t2 - t1).count();

  world_->Step(static_cast<float>(scene_.dt), static_cast<int>(scene_.velocity_iterations),
               static_cast<int>(scene_.position_iterations));
  ++step_;
  // Time from the integer step count: no drift over millions of steps.
  t_ = (static_cast<double>(step_) - static_cast<double>(open_step_)) * scene_.dt;
  if (setup_.drive.vibrating()) offset_ = {walls_->GetPosition().x / L_, walls_->GetPosition().y / L_};
  Clock::time_point t3;
  if (profiling_) {
    t3 = Clock::now(), times_.box2d += std::chrono::duration<double>(t3 - t2).count();
    const b2Profile& prof = world_->GetProfile();  // ms
    times_.contacts += 1e-3 * prof.collide;
    times_.solver += 1e-3 * prof.solve;
    times_.toi += 1e-3 * prof.solveTOI;
  }

  handle_exits();
  if (open_) {
    apply_clog_rule();
    clogs_.on_step_end(
        t_, [this] { return blocking_arch(); }, last_);
  }
  record_closed_clogs();
  if (profiling_) times_.bookkeeping += seconds_since(t3), ++times_.steps;
}

bool Silo::still_since_last_kick() {
  // Every grain, not only those near the outlet: a rearrangement higher in the column can still reach the
  // arch.
  std::vector<core::Vec2> now = positions();
  bool still = kick_pos_.size() == now.size();
  for (int i = 0; still && i < particle_count(); ++i) {
    const double limit = scene_.arrest_skip_shift * radius_[i];
    const core::Vec2 d = now[i] - kick_pos_[i];
    still = core::dot(d, d) <= limit * limit;
  }
  kick_pos_ = std::move(now);
  return still;
}

void Silo::start_skip() {
  // Called at a kick, before it is applied: from here to the step at which the clog rule falls due, step()
  // integrates nothing (skipped_step). Each kick in between is drawn and not applied, so the generator is
  // where an integrated run would have left it, and the rule then fires at the step it would have fired at.
  std::uint64_t target = step_ + 1;
  while (!clogs_.rule_due((static_cast<double>(target) - static_cast<double>(open_step_)) * scene_.dt))
    ++target;
  skip_until_ = target;
  still_kicks_ = 0;
  ++arrest_skips_;
}

void Silo::skipped_step(bool kick_due) {
  if (kick_due && setup_.drive.kick_impulse_max > 0)
    draw_kicks(rng_kick_, setup_.drive.kick_impulse_max, setup_.drive.global_kick, particle_count(),
               scratch_kick_);
  ++step_;
  t_ = (static_cast<double>(step_) - static_cast<double>(open_step_)) * scene_.dt;
  skipped_s_ += scene_.dt;
  if (step_ < skip_until_) return;
  // The packing stood still: no exits; the rule fires as in an integrated run.
  skip_until_ = 0;
  apply_clog_rule();
  record_closed_clogs();
  hold_pos_ = positions();
  kick_pos_.clear();
}

void Silo::record_closed_clogs() {
  // The run's clog list grows by what the tracker reported in this step.
  events_.clogs.insert(events_.clogs.end(), last_.clogs_closed.begin(), last_.clogs_closed.end());
}

void Silo::advance_to(double t) {
  while (t_ < t - 0.01 * scene_.dt) step();
}

double Silo::ExitDirection::mean_velocity_deg() const {
  return exits > 0 ? std::atan2(sum_vx, -sum_vy) * 180.0 / M_PI : NAN;
}
double Silo::ExitDirection::angle_sd_deg() const {
  if (exits < 2) return NAN;
  const double n = static_cast<double>(exits), mean = sum_angle / n;
  return std::sqrt(std::max(0.0, (sum_angle2 - n * mean * mean) / (n - 1))) * 180.0 / M_PI;
}

void Silo::handle_exits() {
  const auto n = static_cast<size_t>(particle_count());
  if (crossed_.size() != n) crossed_.assign(n, 0), crossing_v_.assign(n, {0, 0});
  for (int i = 0; i < particle_count(); ++i) {
    if (!parked_.empty() && parked_[static_cast<size_t>(i)]) continue;
    core::Vec2 p = pos(i);
    const core::Vec2 v = vel(i);
    check_health_fast(i, p, v);
    // Read only: the velocity as the centre passes the outlet's line, for the exit direction.
    if (open_ && p.y < 0 && !crossed_[static_cast<size_t>(i)])
      crossed_[static_cast<size_t>(i)] = 1, crossing_v_[static_cast<size_t>(i)] = v;
    // A disk wholly below the aperture line has fallen clear of it: one exit, then back to the top.
    if (open_ && p.y < -extent_[i]) {
      if (crossed_[static_cast<size_t>(i)]) {
        const core::Vec2 c = crossing_v_[static_cast<size_t>(i)];
        const double angle = std::atan2(c.x, -c.y);
        exit_direction_.exits += 1;
        exit_direction_.sum_vx += c.x, exit_direction_.sum_vy += c.y;
        exit_direction_.sum_angle += angle, exit_direction_.sum_angle2 += angle * angle;
      }
      crossed_[static_cast<size_t>(i)] = 0;
      events_.exits.push_back({t_, i, species_[i]});
      ++exits_by_species_[static_cast<size_t>(core::species_index(species_[i]))];
      last_.exits.push_back(events_.exits.back());
      clogs_.on_exit(t_, last_);
      if (scene_.drain)
        park(i);
      else
        reinject(i);
    }
  }
}

void Silo::park(int id) {
  parked_[static_cast<size_t>(id)] = 1;
  // Out of the world first (its broad-phase proxy goes where it exited), then put below the outlet, out of
  // every camera's view and within the trajectory readers' reach (ten container sizes): a disabled body's
  // move touches no broad phase, so where it is parked cannot change the run.
  bodies_[id]->SetEnabled(false);
  place(id, {0.0, -2.0 * geo_.total_height - 1.0});
  // Its dipole leaves with it.
  const auto k = std::find(dipole_ids_.begin(), dipole_ids_.end(), id);
  if (k != dipole_ids_.end()) {
    dipole_moment_.erase(dipole_moment_.begin() + (k - dipole_ids_.begin()));
    dipole_ids_.erase(k);
  }
  if (--drain_.remaining == 0) drain_.outcome = "emptied", drain_.end_s = t_;
}

void Silo::apply_clog_rule() {
  if (!clogs_.rule_due(t_)) return;
  if (scene_.drain) {
    // Drained grains are not re-injected and the arch is not removed: a clog this long is the jam.
    drain_.outcome = "jammed", drain_.end_s = t_;
    return;
  }
  const std::vector<core::Vec2> p = positions();
  // The visible set is looked for from the disk nearest the outlet up to one aperture width farther.
  double nearest = INFINITY;
  for (const auto& q : p)
    if (q.y > 0) nearest = std::min(nearest, core::length(q));
  const double range = nearest + scene_.aperture;
  core::ArchEvent ev;
  ev.t = t_;
  ev.clog_duration = clogs_.since_last(t_);
  ev.method = arch_method_;
  ev.ids = ev.method == core::ArchMethod::Visible ? core::visible_from_aperture(p, radius_, range)
                                                  : current_arch();
  if (ev.ids.empty()) {
    // Named fallback: the other method, counted and recorded with the event.
    ++arch_fallbacks_;
    ev.method =
        arch_method_ == core::ArchMethod::Visible ? core::ArchMethod::ContactPath : core::ArchMethod::Visible;
    ev.ids = ev.method == core::ArchMethod::Visible ? core::visible_from_aperture(p, radius_, range)
                                                    : current_arch();
  }
  remove_arch(std::move(ev), p);
}

void Silo::remove_arch(core::ArchEvent ev, const std::vector<core::Vec2>& p) {
  for (int id : ev.ids) {
    ev.species.push_back(species_[id]);
    ev.x.push_back(static_cast<float>(p[id].x));
    ev.y.push_back(static_cast<float>(p[id].y));
  }
  ev.geometry = core::arch_geometry(ev.ids, p, radius_);
  record_arch_forces(ev);
  for (int id : ev.ids) reinject(id);
  events_.arches.push_back(std::move(ev));
  clogs_.on_rule(t_, events_.arches.back(), last_);
}

void Silo::reinject(int id) {
  if (setup_.tilt != 0) return reinject_tilted(id);
  const double r = extent_[id];
  // Just above the packed column (disks in flight do not raise it; the free-space test below avoids them).
  const double top = column_top(id);
  const double ceiling = geo_.total_height - r - 1e-4;
  const double y0 = std::min(top + scene_.reinject_gap + r, ceiling);
  // Bands one diameter apart: from just above the column up to the lid, then (rarely: disks flying high)
  // below.
  std::vector<double> bands;
  for (double y = y0; y <= ceiling; y += 2 * r) bands.push_back(y);
  for (double y = y0 - 2 * r; y >= r; y -= 2 * r) bands.push_back(y);
  for (double y : bands) {
    const double lo = geo_.left_at(y) + r + 1e-4, hi = geo_.right_at(y) - r - 1e-4;
    if (hi <= lo) continue;
    for (int attempt = 0; attempt < 40; ++attempt) {
      core::Vec2 p{rng_reinject_.uniform(lo, hi), y};
      if (!free_at(p, id)) continue;
      put_back(id, p);
      return;
    }
  }
  no_room_to_reinject(id);
}

bool Silo::free_at(core::Vec2 p, int id) const {
  const double r = extent_[id];
  bool free = !geo_.obstacle.present() || geo_.obstacle.gap(p) >= r;
  for (int j = 0; j < particle_count() && free; ++j) {
    if (j == id) continue;
    core::Vec2 d = p - pos(j);
    double rr = r + extent_[j];
    free = core::dot(d, d) >= rr * rr;
  }
  return free;
}

void Silo::put_back(int id, core::Vec2 p) {
  place(id, p);
  // A polygon comes back at a random orientation (its own stream: disks draw nothing).
  if (sides_[id] > 0)
    bodies_[id]->SetTransform(bodies_[id]->GetPosition(),
                              static_cast<float>(rng_orient_.uniform(0.0, 2.0 * core::kPi)));
}

void Silo::no_room_to_reinject(int id) const {
  throw core::RuntimeFault("no free space to re-inject particle " + std::to_string(id) +
                           " at t = " + fmt4(t_) +
                           " s: the top of the container is full (the outlet passes grains faster than they "
                           "can fall clear of the top); a taller container (hopper_height or silo_height) or "
                           "fewer grains leaves room");
}

core::Frame Silo::frame(bool with_forces) const {
  core::Frame f;
  f.t = t_;
  f.step = step_;
  f.particles.resize(bodies_.size());
  for (int i = 0; i < particle_count(); ++i) {
    const b2Body* b = bodies_[i];
    core::Particle& p = f.particles[i];
    p.x = static_cast<float>(b->GetPosition().x / L_);
    p.y = static_cast<float>(b->GetPosition().y / L_);
    p.angle = b->GetAngle();
    p.vx = static_cast<float>(b->GetLinearVelocity().x / L_);
    p.vy = static_cast<float>(b->GetLinearVelocity().y / L_);
    p.radius = static_cast<float>(radius_[i]);
    p.force = 0;
    p.species = species_[i];
    p.sides = sides_[i];
  }
  f.container_x = offset_.x;
  f.container_y = offset_.y;
  // Contact forces from the last step's impulses, or their mean over the frame (average_forces; internal
  // units: impulse * L).
  const double to_newton = 1.0 / (L_ * scene_.dt);
  for (const b2Contact* c = with_forces ? world_->GetContactList() : nullptr; c; c = c->GetNext()) {
    if (!c->IsTouching()) continue;
    const b2Manifold* m = c->GetManifold();
    int a = decode(c->GetFixtureA()), b = decode(c->GetFixtureB());
    const Impulses impulse = impulses(c, a, b);  // the last step's, or the mean over the frame
    const double tangential = impulse.tangent;
    float force = static_cast<float>(impulse.normal * to_newton);
    // A grain re-injected at the top after the step still has its contact with the grain it touched below
    // the outlet: the pair no longer touches in this frame's positions, so the frame does not list it.
    if (a >= 0 && b >= 0 && !core::within_reach(f.particles[a], f.particles[b])) continue;
    if (a >= 0) f.particles[a].force += force;
    if (b >= 0) f.particles[b].force += force;
    if (m->pointCount == 0 || (a < 0 && b < 0)) continue;
    // The whole contact as core::ContactForce has it (the same as contact_forces()): b a grain.
    b2WorldManifold wm;
    c->GetWorldManifold(&wm);
    double px = 0, py = 0;
    for (int k = 0; k < m->pointCount; ++k) px += wm.points[k].x, py += wm.points[k].y;
    core::Contact k{a, b, force};
    k.ft = static_cast<float>(tangential * to_newton);
    k.px = static_cast<float>(px / m->pointCount / L_), k.py = static_cast<float>(py / m->pointCount / L_);
    k.nx = wm.normal.x, k.ny = wm.normal.y;
    if (b < 0) std::swap(k.a, k.b), k.nx = -k.nx, k.ny = -k.ny;
    (k.a >= 0 ? f.contacts : f.wall_contacts).push_back(k);
  }
  // The open clog as the step reported it: a frame shows an arch only while a clog is open.
  const core::ClogState& clog = clogs_.state();
  if (open_ && clog.open) {
    // Drawn only while it stands: between two arch checks a kick can part it before the next check drops it.
    if (chain_touches(clog.arch)) f.arch = clog.arch;
    f.clog_open = true;
    f.clog_arrested = clog.arrested;
  }
  f.clog_number = clog.number;
  f.clog_start = clog.start;
  f.rule_due_in = open_ ? clogs_.rule_due_in(t_) : INFINITY;
  f.since_last_exit = open_ ? clogs_.since_last(t_) : 0;
  f.exits = exits_by_species_;
  return f;
}

const core::StepEvents& Silo::finish() {
  last_.clear();
  clogs_.finish(t_, last_);
  record_closed_clogs();
  pending_.append(last_);
  return last_;
}

long Silo::contacts(bool touching_only) const {
  long n = 0;
  for (const b2Contact* c = world_->GetContactList(); c; c = c->GetNext())
    n += !touching_only || c->IsTouching();
  return n;
}

void Silo::step_box2d_only(int n) {
  for (int i = 0; i < n; ++i)
    world_->Step(static_cast<float>(scene_.dt), static_cast<int>(scene_.velocity_iterations),
                 static_cast<int>(scene_.position_iterations));
}

}  // namespace sim
