// siloscope inside Python (pybind11, Debian's pybind11-dev): a scene stepped in process, its grains,
// contacts, arches and events read as numpy arrays between steps, and the keys that may change during a run
// set between them. The same scene and seed stepped here give the events `siloscope run` writes, byte for
// byte (the same sim::Silo, the same event writers). The Python side (siloscope/_simulation.py) wraps this
// module.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/model.h"
#include "core/scene.h"
#include "io/events_csv.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/run.h"
#include "render/camera.h"
#include "render/context.h"
#include "render/free_space.h"
#include "render/overlay.h"
#include "render/painter.h"
#include "render/palette.h"
#include "sim/silo.h"

namespace py = pybind11;

namespace {

// The keys set() takes, with what each changes.
const char* kSettable =
    "kick_impulse_max (N*s: the random kicks from the next kick on; 0: none), outlet_open (true/false: the "
    "lid back across the outlet, or away)";

// One thread in a Simulation at a time: a second one (stepping or reading while the first steps with the
// GIL released) gets a RuntimeError instead of Box2D's abort. Two Simulations in two threads run freely.
class Busy {
 public:
  Busy(std::atomic<bool>& flag, const char* what) : flag_(flag) {
    if (flag_.exchange(true))
      throw std::runtime_error(std::string(what) +
                               "(): this Simulation is being stepped by another thread; use one Simulation "
                               "per thread (they run in parallel), or a lock around its calls");
  }
  ~Busy() { flag_ = false; }
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  std::atomic<bool>& flag_;
};

// Pictures in process: record's renderer on an off-screen context of the calling thread (OSMesa: one per
// thread that draws, made at its first picture and current on it from then on).
struct Pictures {
  render::OffscreenContext context;
  render::Painter painter;
};
Pictures& pictures() {
  thread_local std::unique_ptr<Pictures> p;
  if (!p) p = std::make_unique<Pictures>();
  return *p;
}

class Simulation {
 public:
  // `scene`: a scene file (or a run's metadata.toml), or "" for the built-in default scene; `keys`:
  // "key=value" overrides as `--set` takes them; `seed` < 0: the scene's own.
  Simulation(const std::string& scene, long long seed, const std::vector<std::string>& keys) {
    core::Scene s = scene.empty() ? core::Scene{} : core::load_scene(scene);
    core::apply_overrides(s, keys);
    if (seed >= 0) s.seed = static_cast<std::uint64_t>(seed), s.origin["seed"] = "seed=";
    silo_ = std::make_unique<sim::Silo>(core::compile(s));
  }

  // Step n time steps; returns the events of those steps (also kept for events()). Ctrl-C stops it between
  // two steps within about 20 ms (KeyboardInterrupt; the steps done stand, their events come with the next
  // call).
  py::dict step(long n) {
    if (n < 0) throw core::InputError("step(n): n = " + std::to_string(n) + " must be >= 0");
    const Busy busy(busy_, "step");
    stepping([&](long k) { return k < n; });
    last_ = silo_->take_events();
    return events_dict(last_);
  }
  // Step until time() >= t (s since the outlet opened), as Silo::advance_to does.
  py::dict advance_to(double t) {
    if (!std::isfinite(t) || t < silo_->time() - 0.01 * silo_->scene().dt)
      throw core::InputError("advance_to(t): t = " + core::format_shortest(t) +
                             " s: expected a finite time from now (" + core::format_shortest(silo_->time()) +
                             " s) on");
    const Busy busy(busy_, "advance_to");
    const double dt = silo_->scene().dt;
    stepping([&](long) { return silo_->time() < t - 0.01 * dt; });
    last_ = silo_->take_events();
    return events_dict(last_);
  }
  double time() const { return silo_->time(); }
  double dt() const { return silo_->scene().dt; }
  int n() const { return silo_->particle_count(); }

  // Grains now: (n, 2) arrays in the container's frame (m, m/s), angles (rad), radii (m), species index.
  py::array_t<double> positions() const {
    const auto p = silo_->positions();
    py::array_t<double> out({static_cast<py::ssize_t>(p.size()), py::ssize_t{2}});
    auto a = out.mutable_unchecked<2>();
    for (size_t i = 0; i < p.size(); ++i) a(i, 0) = p[i].x, a(i, 1) = p[i].y;
    return out;
  }
  py::dict grains() const {
    const core::Frame f = silo_->frame(false);
    const auto n = static_cast<py::ssize_t>(f.particles.size());
    py::array_t<double> v({n, py::ssize_t{2}}), angle(n), radius(n);
    py::array_t<int> species(n), sides(n);
    auto va = v.mutable_unchecked<2>();
    auto an = angle.mutable_unchecked<1>(), ra = radius.mutable_unchecked<1>();
    auto sp = species.mutable_unchecked<1>(), si = sides.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& q = f.particles[static_cast<size_t>(i)];
      va(i, 0) = q.vx, va(i, 1) = q.vy;
      an(i) = q.angle, ra(i) = silo_->radii()[static_cast<size_t>(i)];
      sp(i) = static_cast<int>(q.species), si(i) = q.sides;
    }
    py::dict d;
    d["position"] = positions();
    d["velocity"] = v;
    d["angle"] = angle;
    d["radius"] = radius;
    d["species"] = species;
    d["sides"] = sides;
    return d;
  }
  std::vector<std::string> species_names() const { return silo_->setup().species_names(); }

  // Grain-grain contacts now, with their forces over the last step (N: normal, and tangential along (ny,
  // -nx)), where they touch (m) and their unit normal from a to b (core::Contact).
  py::dict contacts() const {
    const core::Frame f = silo_->frame(true);
    const auto n = static_cast<py::ssize_t>(f.contacts.size());
    py::array_t<int> a(n), b(n);
    py::array_t<double> force(n), ft(n), x(n), y(n), nx(n), ny(n);
    auto aa = a.mutable_unchecked<1>(), bb = b.mutable_unchecked<1>();
    auto ff = force.mutable_unchecked<1>(), tt = ft.mutable_unchecked<1>();
    auto xx = x.mutable_unchecked<1>(), yy = y.mutable_unchecked<1>();
    auto nnx = nx.mutable_unchecked<1>(), nny = ny.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& c = f.contacts[static_cast<size_t>(i)];
      aa(i) = c.a, bb(i) = c.b, ff(i) = c.force, tt(i) = c.ft;
      xx(i) = c.px, yy(i) = c.py, nnx(i) = c.nx, nny(i) = c.ny;
    }
    py::dict d;
    d["a"] = a;
    d["b"] = b;
    d["force"] = force;
    d["ft"] = ft;
    d["x"] = x;
    d["y"] = y;
    d["nx"] = nx;
    d["ny"] = ny;
    return d;
  }
  // The open clog (None when flowing) and the arch standing over the outlet now.
  py::object clog() const {
    const core::ClogState& c = silo_->clog();
    if (!c.open) return py::none();
    py::dict d;
    d["number"] = c.number;
    d["start_s"] = c.start;
    d["arrested"] = c.arrested;
    d["arch"] = c.arch;
    return d;
  }
  std::vector<int> arch() const { return silo_->current_arch(); }

  // Every exit so far: the columns of exits.csv.
  py::dict exits() const {
    const auto& e = silo_->events().exits;
    const auto n = static_cast<py::ssize_t>(e.size());
    py::array_t<double> t(n);
    py::array_t<int> id(n), sp(n);
    auto tt = t.mutable_unchecked<1>();
    auto ii = id.mutable_unchecked<1>(), ss = sp.mutable_unchecked<1>();
    for (py::ssize_t k = 0; k < n; ++k) {
      const auto& x = e[static_cast<size_t>(k)];
      tt(k) = x.t, ii(k) = x.id, ss(k) = static_cast<int>(core::species_index(x.species));
    }
    py::dict d;
    d["t_s"] = t;
    d["id"] = id;
    d["species"] = sp;
    return d;
  }
  // The event files `run` writes, as their text: exits.csv, clogs.csv, arches.csv.
  py::dict event_files() const {
    const auto names = silo_->setup().species_names();
    py::dict d;
    d[io::run_file::kExits] = io::exits_csv(silo_->events(), names);
    d[io::run_file::kClogs] = io::clogs_csv(silo_->events());
    d[io::run_file::kArches] = io::arches_csv(silo_->events(), names);
    return d;
  }
  // Close the open clog as censored, as a run's end does (once, at the end).
  void finish() {
    if (finished_) throw core::InputError("finish(): already finished");
    silo_->finish();
    last_ = silo_->take_events();
    finished_ = true;
  }
  py::dict last_events() const { return events_dict(last_); }

  void set(const std::string& key, py::object value) {
    if (key == "kick_impulse_max") {
      const double j = value.cast<double>();
      if (!(j >= 0) || !std::isfinite(j))
        throw core::InputError("set(\"kick_impulse_max\", " + core::format_shortest(j) +
                               "): expected a finite impulse >= 0 N*s");
      silo_->set_kick_impulse_max(j);
    } else if (key == "outlet_open") {
      if (!py::isinstance<py::bool_>(value))
        throw core::InputError("set(\"outlet_open\", ...): expected True or False");
      silo_->set_outlet_open(value.cast<bool>());
    } else {
      throw core::InputError("set(\"" + key + "\"): not a key that may change during a run; those are " +
                             kSettable + ". Other keys: a new Simulation(..., " + key + "=...)");
    }
  }
  bool outlet_open() const { return silo_->outlet_open(); }

  // The simulation now as record draws it: an (height, width, 3) RGB array, `camera` and `overlay` as
  // record's
  // --camera and --overlay, `color` as its --color, the dark background if asked. Each picture stands alone
  // (no trails or layout carried over from the last); the boxes go where they cover the fewest grains, as the
  // inspector's snapshots place them (a picture has no margin beside the container).
  py::array_t<std::uint8_t> picture(int width, int height, const std::string& camera,
                                    const std::string& overlay, const std::string& color, bool dark) const {
    if (width < 16 || height < 16 || width > 8192 || height > 8192)
      throw core::InputError("render(width=" + std::to_string(width) + ", height=" + std::to_string(height) +
                             "): each side 16 to 8192 pixels");
    render::Style style;
    style.dark = dark;
    style.color = render::parse_color_mode(color);
    render::OverlayOptions o = render::parse_overlay(overlay);
    o.place_clear = !o.plot;  // the information box where it covers the fewest grains, as snapshots place it
    const core::Frame f =
        silo_->frame(style.color == render::ColorMode::Force || style.color == render::ColorMode::Stress);
    const render::CameraSpec cam = render::parse_camera(camera);
    const core::Geometry& geo = silo_->geometry();
    render::OverlayData od = render::overlay_data_for(silo_->model());
    // Where the container leaves the boxes no clear space, a margin on the right holds them (as frame's and
    // the inspector's snapshots keep one).
    if (o.any())
      od.margin_w = render::overlay_margin(
          [&](int w) {
            return std::vector<std::vector<render::View>>{render::layout_views(cam, geo, w, height)};
          },
          geo, o, 0, width, height, od.species_names, od.title,
          !render::color_scale_label(style).empty() || style.chains);
    const auto views = render::layout_views(cam, geo, width - od.margin_w, height);
    core::Image img;
    {
      py::gil_scoped_release free;
      Pictures& p = pictures();
      p.painter.start_afresh();
      img = p.painter.paint(f, geo, views, style, o, od, width, height);
    }
    py::array_t<std::uint8_t> out(
        {static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width), py::ssize_t{3}});
    auto a = out.mutable_unchecked<3>();
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::uint8_t* px = img.pixel(x, y);
        a(y, x, 0) = px[0], a(y, x, 1) = px[1], a(y, x, 2) = px[2];
      }
    return out;
  }
  std::string scene_toml() const { return core::scene_toml(silo_->scene()); }
  std::uint64_t seed() const { return silo_->scene().seed; }

 private:
  py::dict events_dict(const core::StepEvents& e) const {
    py::dict d;
    py::list exits, opened, closed, removed;
    for (const auto& x : e.exits) exits.append(py::make_tuple(x.t, x.id, core::species_index(x.species)));
    for (int number : e.clogs_opened) opened.append(number);
    for (const auto& c : e.clogs_closed) closed.append(py::make_tuple(c.start, c.end, c.arrested));
    for (const auto& a : e.rule_removed) removed.append(py::make_tuple(a.t, a.ids));
    d["exits"] = exits;
    d["clogs_opened"] = opened;
    d["clogs_closed"] = closed;
    d["rule_removed"] = removed;
    return d;
  }
  // Steps while more(k) for the k-th step, the GIL released; every 20 ms it takes the GIL back to let Python
  // handle a signal (Ctrl-C raises KeyboardInterrupt here, between two steps).
  template <class More>
  void stepping(More more) {
    using clock = std::chrono::steady_clock;
    py::gil_scoped_release free;
    auto next_check = clock::now() + std::chrono::milliseconds(20);
    for (long k = 0; more(k); ++k) {
      silo_->step();
      if ((k & 63) == 63 && clock::now() >= next_check) {
        py::gil_scoped_acquire held;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        next_check = clock::now() + std::chrono::milliseconds(20);
      }
    }
  }
  std::unique_ptr<sim::Silo> silo_;
  core::StepEvents last_;
  bool finished_ = false;

 public:
  mutable std::atomic<bool> busy_{false};  // a thread is inside (Busy)
};

// A reader or setter of `Simulation` wrapped in its Busy guard, under `name`.
template <class R, class... A>
auto guarded(R (Simulation::*f)(A...) const, const char* name) {
  return [f, name](const Simulation& s, A... a) {
    const Busy busy(s.busy_, name);
    return (s.*f)(a...);
  };
}
template <class R, class... A>
auto guarded(R (Simulation::*f)(A...), const char* name) {
  return [f, name](Simulation& s, A... a) {
    const Busy busy(s.busy_, name);
    return (s.*f)(std::move(a)...);
  };
}

}  // namespace

PYBIND11_MODULE(_siloscope, m) {
  m.doc() = "siloscope's simulation in process (wrapped by siloscope.Simulation)";
  m.attr("version") = io::version_string();
  m.attr("settable_keys") = kSettable;
  py::register_exception<core::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<core::Unstable>(m, "Unstable", PyExc_RuntimeError);
  py::register_exception<core::RuntimeFault>(m, "RuntimeFault", PyExc_RuntimeError);
  // The C++ readers' checks, so that the package reads a run's files as the binary does (one reader per file
  // kind): a file's FNV-1a 64 hash (the manifest's), a run opened and its whole manifest checked, a run's
  // contacts read with their bounds and tied to its trajectory. Each raises ValueError with the binary's
  // message.
  m.def("file_hash", [](const std::string& path) { return io::file_hash(path); });
  m.def("check_run", [](const std::string& path) { (void)io::Run::open(path, "read_run"); });
  m.def("check_contacts", [](const std::string& path) {
    const io::Run run = io::Run::open(path, "read_contacts", io::Run::kTrajectory);
    (void)run.contacts();
  });
  py::class_<Simulation>(m, "Simulation")
      .def(py::init<const std::string&, long long, const std::vector<std::string>&>())
      .def("step", &Simulation::step)
      .def("advance_to", &Simulation::advance_to)
      .def_property_readonly("time", &Simulation::time)
      .def_property_readonly("dt", &Simulation::dt)
      .def_property_readonly("n", &Simulation::n)
      .def_property_readonly("seed", &Simulation::seed)
      .def("positions", guarded(&Simulation::positions, "positions"))
      .def("grains", guarded(&Simulation::grains, "grains"))
      .def("species_names", &Simulation::species_names)
      .def("contacts", guarded(&Simulation::contacts, "contacts"))
      .def("clog", guarded(&Simulation::clog, "clog"))
      .def("arch", guarded(&Simulation::arch, "arch"))
      .def("exits", guarded(&Simulation::exits, "exits"))
      .def("event_files", guarded(&Simulation::event_files, "event_files"))
      .def("finish", guarded(&Simulation::finish, "finish"))
      .def("last_events", guarded(&Simulation::last_events, "last_events"))
      .def("set", guarded(&Simulation::set, "set"))
      .def_property_readonly("outlet_open", &Simulation::outlet_open)
      .def("render", guarded(&Simulation::picture, "render"))
      .def("scene_toml", guarded(&Simulation::scene_toml, "scene_toml"));
}
