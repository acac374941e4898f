// Cameras and views: which window of the world (metres) appears where in the image (pixels). Pure math, no
// GL. Pixel coordinates have their origin at the top-left corner, x to the right, y down; world y points up.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/geometry.h"

namespace render {

struct Camera {
  double cx = 0, cy = 0;  // m, the world point at the centre of the view
  double height = 1;      // m of world shown from the top to the bottom of the view
  double angle = 0;       // rad: the world turned counter-clockwise on screen (a tilted container stands so)
};

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;  // pixels, top-left origin
};

struct View {
  Camera cam;
  Rect rect;
  std::string name;  // "hopper", "outlet", "window"

  double px_per_m() const { return rect.h / cam.height; }
  core::Vec2 world_to_pixel(core::Vec2 p) const;
  core::Vec2 pixel_to_world(core::Vec2 px) const;
  // Column-major 3x3 matrix taking world (x, y, 1) to clip coordinates of this view's viewport.
  std::array<float, 9> world_to_clip() const;
};

// Parse "WIDTHxHEIGHT" for `option` (named in the error), each side at least min_w x min_h pixels.
// Throws core::InputError.
void parse_size(const std::string& text, const std::string& option, int& w, int& h, int min_w = 1,
                int min_h = 1);

// A camera showing the world window [x0, x1] x [y0, y1] whole, centred, in a view of w x h pixels, the world
// turned by `angle` (rad, counter-clockwise).
Camera fit(double x0, double y0, double x1, double y1, int w, int h, double angle = 0);

// Where a camera's subject is over time, found by simulating ahead (app/services/recording.h): a grain's
// centre at increasing times (m, world frame), read between samples by straight lines.
struct SubjectTrack {
  std::vector<double> t, x, y;
  core::Vec2 at(double time) const;
};

// A followed grain that vanishes in one sample (taken out by the clog rule and re-injected on top, or gone
// through the outlet) would take the camera with it in one frame, and the event would happen off screen: the
// track holds where the grain was for `hold` s after any jump longer than `jump` (m), then glides to it over
// `glide` s (smoothstep). Returns the number of jumps held.
int hold_through_jumps(SubjectTrack& track, double jump, double hold = 1.0, double glide = 1.0);

// What a camera shows, parsed once from its text:
//   hopper          the whole container
//   outlet          the outlet region, ten original diameters tall (from 1.9 diameters below the aperture),
//                   at most 9.2 diameters wide: 1.3 m x 1.2 m for the paper's 0.13 m disks
//   split           the whole container in a strip on the left, the outlet in the rest
//   window:X0,Y0,X1,Y1   any window in metres
//   arch:K          the arch of the K-th clog (row K of clogs.csv) as it forms, whole, with a diameter and a
//                   half around it and at least six diameters tall (grown mostly upwards: what it holds)
//   grain:ID        grain ID (0-based, as in the trajectory), followed: eight diameters tall, centred on it
// arch and grain are known only by simulating ahead: `record` resolves them (with_subjects below); every
// other command refuses them.
struct CameraSpec {
  enum class Kind { Hopper, Outlet, Split, Window, Arch, Grain } kind = Kind::Split;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;      // Window, and Arch once resolved, m
  int subject = 0;                            // Arch: the clog's number K >= 1; Grain: the grain's id
  std::shared_ptr<const SubjectTrack> track;  // Grain, once resolved
  std::string text = "split";                 // as written: metadata, panels, messages
  bool names_subject() const { return kind == Kind::Arch || kind == Kind::Grain; }
  bool resolved() const { return kind == Kind::Arch ? x1 > x0 : kind != Kind::Grain || track != nullptr; }
};
// Throws core::InputError naming the spec and the allowed forms; arch:K and grain:ID only `with_subjects`.
CameraSpec parse_camera(const std::string& spec, bool with_subjects = false);

// The window that shows an arch whose grains have these centres and radii (m): arch:K's, once found.
void frame_arch(CameraSpec& camera, const std::vector<core::Vec2>& centres, double max_radius,
                double grain_diameter);

// The views of a camera in an image of w x h pixels (a grain followed: where it is at simulated time t).
// Throws core::InputError for an arch or grain camera not yet resolved.
std::vector<View> layout_views(const CameraSpec& camera, const core::Geometry& geo, int w, int h,
                               double t = 0);

// A camera move: key frames "T:CAMERA,T:CAMERA,..." (simulated seconds, increasing; each camera hopper,
// outlet, window:X0,Y0,X1,Y1, arch:K or grain:ID: one view, since a path moves one view; a key that follows a
// grain is evaluated where the grain is at each frame, in its glides too). Before the first key and after the
// last the camera stands still; between two keys it glides with an ease in and out (smoothstep): a zoom at a
// steady rate (the height shown geometrically) about the point that sits at the same place in both keys'
// pictures, so whatever both keys show (the outlet, between the hopper and the outlet) stays in the picture
// throughout; a pan when the heights are equal. Two keys at the same camera hold it.
struct CameraPath {
  struct Key {
    double t;
    CameraSpec camera;
  };
  std::vector<Key> keys;
  std::string text;  // as written: metadata
  bool empty() const { return keys.empty(); }
  // The single view at simulated time t in an image of w x h pixels.
  View view_at(double t, const core::Geometry& geo, int w, int h) const;
};
// Throws core::InputError naming the key and what is allowed; arch:K and grain:ID keys only `with_subjects`.
CameraPath parse_camera_path(const std::string& spec, bool with_subjects = false);
// A camera naming a subject (arch:K, grain:ID) as a path of one key at 0 s, so that it moves as its subject
// does; an empty path for any other camera.
CameraPath subject_path(const CameraSpec& camera);

// Whether view v shows every disk (centres and radii, m) whole.
bool shows_disks(const View& v, const std::vector<core::Vec2>& centres, const std::vector<double>& radii);
// View v widened about its own pixel rectangle (the same angle) as little as needed to show every disk whole
// with `pad` metres around it: a freeze's picture of an arch the camera had partly out of view.
View widened_to_show(const View& v, const std::vector<core::Vec2>& centres, const std::vector<double>& radii,
                     double pad);

// A freeze: a movie or clip holds its picture for `seconds` of video at each event, a clog opening (as the
// simulation's step reports it, core/events.h) or the last frame before the clog rule fires.
struct Freeze {
  enum class At { None, Clog, Rule } at = At::None;
  double seconds = 0;
  std::string text;  // as written: metadata
  explicit operator bool() const { return at != At::None; }
  // Copies to add after the event's own frame at `fps` video frames per second.
  long copies(double fps) const;
  const char* caption() const { return at == At::Clog ? "clog formed" : "the clog rule fires next"; }
};
// Whether a movie or a clip holds its picture at `now` (`before`: the frame before it; null for the first):
// the one rule for record, the inspector's clips and anything else that freezes. At a clog: the first frame
// that shows the clog's arch (from its formation, in hindsight) or, without one, the clog's opening. At the
// rule: the last frame before the rule fires (`rule_next`, which the caller knows from its events).
bool freeze_fires(const Freeze& fz, const core::Frame* before, const core::Frame& now, bool rule_next);
// EVENT and SECONDS (clog or rule; 0 < SECONDS <= 60); throws core::InputError naming `what` was given and
// the `form` expected.
Freeze parse_freeze(const std::string& event, const std::string& seconds, const std::string& what,
                    const std::string& form);

}  // namespace render
