// The windows' sources and sinks (ui/sources.h) made from io and record: a trajectory file's frames, PNG and
// MP4 files.
#pragma once

#include "app/services/looks.h"
#include "io/run.h"
#include "ui/inspector.h"
#include "ui/sources.h"

namespace app {

class TrajectoryFrames : public ui::FrameSource {
 public:
  // A run's trajectory, with its contacts when it kept them (recordings do): frames carry them, for force
  // chains and the solver's coordination.
  explicit TrajectoryFrames(const io::Run& run) : t_(run.trajectory()), contacts_(run.contacts()) {}
  // A trajectory read already (the tests' synthetic ones).
  explicit TrajectoryFrames(const io::Trajectory& t, const io::Contacts* contacts = nullptr)
      : t_(t), contacts_(contacts) {}
  long size() const override { return t_.size(); }
  core::Frame frame(long k) const override {
    core::Frame f = t_.frame(k);
    if (contacts_) {
      f.contacts = contacts_->frame(k);
      f.wall_contacts = contacts_->walls(k);
    }
    return f;
  }
  bool has_contacts() const override { return contacts_ && contacts_->size() > 0; }
  bool has_contact_forces() const override { return has_contacts() && contacts_->has_geometry(); }
  double time(long k) const override { return t_.time(k); }
  double since_last_exit(long k) const override { return t_.since_last_exit(k); }
  int long_arches(long k) const override { return t_.long_arches(k); }
  const std::vector<core::ClogEvent>& clogs() const override { return t_.events().clogs; }
  double frame_interval() const override { return t_.info().frame_interval; }
  double clog_min_gap() const override { return t_.info().clog_min_gap; }

 private:
  const io::Trajectory& t_;
  const io::Contacts* contacts_;
};

// An imported lab run (siloscope import) is named as such in the inspector's information box, not by the
// geometry scene's r, chi and mu (which it was not made with).
void title_imported(ui::Inspector& insp, const io::Run& run);
// The look of a picture of `run`: the options given, the recording's own look for the rest, applied to the
// inspector that draws it.
Look apply_look(ui::Inspector& insp, LookOptions looks, const io::Run& run);

class RecordFiles : public ui::ImageFiles {
 public:
  void write_png(const std::string& path, const core::Image& img) const override;
  void check_movie(int width, int height, int fps) const override;
  std::unique_ptr<ui::MovieSink> open_movie(const std::string& path, int width, int height,
                                            int fps) const override;
  void write_vector(const std::string& path, const std::string& draw_list_csv, double width_m,
                    double height_m, const std::string& caption, const std::string& key = "") const override;
  void write_text(const std::string& path, const std::string& text) const override;
  // > 0: vector pictures are laid out as journal figures this many points wide (frame --width), text 7-9 pt.
  double figure_width_pt = 0;
};

}  // namespace app
