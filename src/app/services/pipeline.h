// record's back half, one pipeline for every movie: Frames in; a render thread (its own OSMesa context and
// one render::Painter for all panels) turns them into Images; an encode thread writes the MP4 and every Nth
// frame as PNG. Bounded queues keep memory flat. An error in a stage closes the queues, so every stage stops;
// finish() waits for both threads and rethrows the first error.
#pragma once

#include <atomic>
#include <exception>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/services/queue.h"
#include "core/frame.h"
#include "core/geometry.h"
#include "core/image.h"
#include "render/camera.h"
#include "render/overlay.h"
#include "render/palette.h"

namespace record {
class Mp4Writer;
}

namespace app {

// Where one panel's frames are drawn: its container, its views in the image, its overlay data (owned by the
// caller, alive until finish()).
struct PanelLayout {
  const core::Geometry* geometry;
  const std::vector<render::View>* views;
  const render::OverlayData* overlay_data;
};

// One picture's worth: a frame per panel, and what each panel points out.
struct PipelineFrame {
  std::vector<core::Frame> frames;
  std::vector<render::Annotations> notes;        // one per panel (may be empty: nothing to point out)
  std::vector<std::vector<render::View>> views;  // one per panel where a camera moves (empty: the layout's)
};

struct PipelineOutputs {
  record::Mp4Writer* mp4 = nullptr;  // none: PNG frames only
  std::filesystem::path png_dir;     // frame_NNNNNN.png, every png_every-th frame (0: none)
  int png_every = 0;
};

class FramePipeline {
 public:
  FramePipeline(std::vector<PanelLayout> panels, const render::Style& style,
                const render::OverlayOptions& overlay, int width, int height, PipelineOutputs out,
                bool quiet);
  ~FramePipeline();  // stops and joins the stages if finish() was not called (an error upstream)
  FramePipeline(const FramePipeline&) = delete;
  FramePipeline& operator=(const FramePipeline&) = delete;

  // One frame per panel, in panel order. Blocks while the queue is full; false once a later stage stopped.
  bool push(PipelineFrame frame);
  // No more frames: wait for the stages to drain, rethrow the first stage's error.
  void finish();

  long frames_written() const { return encoded_; }
  const std::string& gl_renderer() const { return gl_renderer_; }
  double draw_seconds() const { return draw_; }
  // Pictures in which a box of the overlay found no clear space and covers part of the subject.
  long covered_frames() const { return covered_; }
  double readback_seconds() const { return readback_; }
  double png_seconds() const { return png_; }

 private:
  void render_stage();
  void encode_stage();
  std::vector<PanelLayout> panels_;
  render::Style style_;
  render::OverlayOptions overlay_;
  int width_, height_;
  PipelineOutputs out_;
  bool quiet_;
  BoundedQueue<PipelineFrame> frames_{8};
  BoundedQueue<core::Image> images_{4};
  // Images the encoder is done with, their buffers reused by the renderer: a fresh 8 MB per 1080p frame
  // would be zero-filled page by page (about a tenth of record's CPU before).
  std::mutex spare_mutex_;
  std::vector<core::Image> spare_;
  std::exception_ptr render_error_, encode_error_;
  std::string gl_renderer_;
  long encoded_ = 0;
  double draw_ = 0, readback_ = 0, png_ = 0;
  std::atomic<long> covered_{0};
  std::thread render_thread_, encode_thread_;
  bool finished_ = false;
};

}  // namespace app
