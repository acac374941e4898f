// What the windows read and write, handed in by the app: ui knows frames and images, not the trajectory file
// format nor the PNG and MP4 writers (app/inspect_files.h implements both from io and record).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/image.h"

namespace ui {

// The recorded frames the inspector steps through.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual long size() const = 0;
  virtual core::Frame frame(long k) const = 0;
  virtual double time(long k) const = 0;             // s
  virtual double since_last_exit(long k) const = 0;  // s: the clog timer at frame k
  virtual int long_arches(long k) const = 0;         // arches the clog rule removed up to frame k
  // The run's clogs as the simulation reported them (the rows of clogs.csv), in order.
  virtual const std::vector<core::ClogEvent>& clogs() const = 0;
  virtual double frame_interval() const = 0;           // s between frames
  virtual double clog_min_gap() const = 0;             // s: a gap at least this long is a clog
  virtual bool has_contacts() const { return false; }  // frames carry their contacts (force chains)
  // Their contacts carry tangential forces, contact points and the walls' contacts: stress can be shown.
  virtual bool has_contact_forces() const { return false; }
};

// "What if": the run continued from one of its frames with changes, simulated by the app
// (app/services/branch.h); the inspector shows it beside the recorded run on one clock.
class Branch {
 public:
  virtual ~Branch() = default;
  virtual long from_frame() const = 0;    // the recorded frame it branched at
  virtual double time() const = 0;        // s, where it stands
  virtual core::Frame frame() const = 0;  // its state now (with forces), as a trajectory's frame
  virtual void advance_to(double t) = 0;  // s; throws core::Unstable with the health monitor's message
  virtual void remove_grain(int id) = 0;  // re-injected above the column (sim::Silo::remove_by_hand)
  virtual void kick(double dv) = 0;       // m/s: every grain lifted by dv at once (sim::Silo::kick_all)
  virtual void set_key(const std::string& key, double value) = 0;  // a drive key from now on
  virtual std::vector<std::string> changes() const = 0;            // what was changed, when, in order
  // Ends it as a run ends (its open clog closed) and writes it as a run directory of its own: the recorded
  // frames up to the branch, then the branch's; its metadata names the run, the frame and the changes.
  // Throws core::InputError when `dir` exists.
  virtual void save(const std::string& dir) = 0;
  virtual bool saved() const = 0;
};

// Makes branches of the run the inspector shows.
class Brancher {
 public:
  virtual ~Brancher() = default;
  // The run rebuilt at frame k from its metadata (the same steps: the same state bit for bit), checked
  // against its recorded events and frame k; throws core::InputError naming what differs.
  virtual std::unique_ptr<Branch> branch(long k) const = 0;
};

// A movie being written: frames in order, then finish() (the file appears only then).
class MovieSink {
 public:
  virtual ~MovieSink() = default;
  virtual void add(const core::Image& img) = 0;
  virtual void finish() = 0;
};

// Where the windows' pictures go.
class ImageFiles {
 public:
  virtual ~ImageFiles() = default;
  // A PNG, written whole under a temporary name and renamed (synced: a snapshot is a user's file).
  virtual void write_png(const std::string& path, const core::Image& img) const = 0;
  // Throws core::InputError naming the value when width x height or fps cannot be encoded.
  virtual void check_movie(int width, int height, int fps) const = 0;
  virtual std::unique_ptr<MovieSink> open_movie(const std::string& path, int width, int height,
                                                int fps) const = 0;
  // A vector picture (.svg or .pdf): a draw list as a table (render::draw_list_csv) of a window width_m x
  // height_m, with a caption; written whole under a temporary name and renamed. Throws core::RuntimeFault
  // when it cannot be made.
  // A text file (a saved session), written whole under a temporary name and renamed.
  virtual void write_text(const std::string& path, const std::string& text) const = 0;
  // A vector picture (SVG, PDF) of a draw list; `key` (tab-separated lines: background, info, species, arch,
  // colorbar, scale) is drawn beside it as vector elements: the information box, legend, colour bar, scale
  // bar.
  virtual void write_vector(const std::string& path, const std::string& draw_list_csv, double width_m,
                            double height_m, const std::string& caption,
                            const std::string& key = "") const = 0;
};

}  // namespace ui
