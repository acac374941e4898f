#include "app/services/pipeline.h"

#include <chrono>
#include <cstdio>

#include "record/mp4.h"
#include "record/png.h"
#include "render/context.h"
#include "render/painter.h"

namespace app {

FramePipeline::FramePipeline(std::vector<PanelLayout> panels, const render::Style& style,
                             const render::OverlayOptions& overlay, int width, int height,
                             PipelineOutputs out, bool quiet)
    : panels_(std::move(panels)),
      style_(style),
      overlay_(overlay),
      width_(width),
      height_(height),
      out_(std::move(out)),
      quiet_(quiet) {
  render_thread_ = std::thread([this] { render_stage(); });
  encode_thread_ = std::thread([this] { encode_stage(); });
}

FramePipeline::~FramePipeline() {
  if (finished_) return;
  frames_.close();
  images_.close();
  if (render_thread_.joinable()) render_thread_.join();
  if (encode_thread_.joinable()) encode_thread_.join();
}

bool FramePipeline::push(PipelineFrame frame) {
  return frames_.push(std::move(frame));
}

void FramePipeline::finish() {
  frames_.close();
  render_thread_.join();
  encode_thread_.join();
  finished_ = true;
  if (render_error_) std::rethrow_exception(render_error_);
  if (encode_error_) std::rethrow_exception(encode_error_);
}

void FramePipeline::render_stage() {
  try {
    render::OffscreenContext ctx;
    gl_renderer_ = ctx.description();
    if (!quiet_) std::fprintf(stderr, "siloscope: OpenGL %s\n", gl_renderer_.c_str());
    render::Painter painter;
    PipelineFrame pf;
    while (frames_.pop(pf)) {
      std::vector<render::PanelInput> in;
      for (size_t k = 0; k < panels_.size(); ++k)
        in.push_back({&pf.frames[k], panels_[k].geometry,
                      k < pf.views.size() ? &pf.views[k] : panels_[k].views, panels_[k].overlay_data,
                      k < pf.notes.size() ? &pf.notes[k] : nullptr});
      core::Image img;
      {
        std::lock_guard lock(spare_mutex_);
        if (!spare_.empty()) img = std::move(spare_.back()), spare_.pop_back();
      }
      painter.paint(img, in, style_, overlay_, width_, height_);
      draw_ = painter.timing().draw_s;
      covered_ += !painter.boxes_clear();
      readback_ = painter.timing().readback_s;
      if (!images_.push(std::move(img))) break;
    }
  } catch (...) {
    render_error_ = std::current_exception();
    frames_.close();
  }
  images_.close();
}

void FramePipeline::encode_stage() {
  try {
    core::Image img;
    while (images_.pop(img)) {
      if (out_.mp4) out_.mp4->add(img);
      if (out_.png_every > 0 && encoded_ % out_.png_every == 0) {
        const auto t0 = std::chrono::steady_clock::now();
        char name[32];
        std::snprintf(name, sizeof name, "frame_%06ld.png", encoded_);
        record::write_png(out_.png_dir / name, img);
        png_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
      ++encoded_;
      std::lock_guard lock(spare_mutex_);
      if (spare_.size() < 4) spare_.push_back(std::move(img));
    }
  } catch (...) {
    encode_error_ = std::current_exception();
    images_.close();
    frames_.close();
  }
}

}  // namespace app
