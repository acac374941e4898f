// A run as one self-contained HTML page (siloscope share): the run's frames packed small (positions on a
// 16-bit grid over the run's extent, angles, velocities and forces quantized, each quantity differenced from
// frame to frame and the whole deflated, base64 in the page), its events, its look, and the viewer
// (src/viewer/: a canvas, no library, no network), which inflates the frames with the browser's own
// DecompressionStream. docs/share.md documents the packing.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "app/services/looks.h"
#include "io/run.h"

namespace app {

struct ShareOptions {
  double from = 0, to = -1;  // s of the run; to < 0: its end
  int stride = 1;            // every stride-th frame
  bool embed = false;        // a fragment for a slide deck or a page (sized by its container)
};

struct SharePage {
  std::string html;
  long frames = 0;             // frames in the page
  std::size_t raw_bytes = 0;   // the packed frames before deflate
  std::size_t data_bytes = 0;  // deflated, before base64
};

// The page for `run` (which must have a trajectory) in `look`; `viewer` is the directory of the viewer's
// files (viewer.html, viewer.js, viewer.css). Throws core::InputError for a window outside the run, and
// core::Interrupted at Ctrl-C.
SharePage share_page(const io::Run& run, const Look& look, const ShareOptions& o,
                     const std::filesystem::path& viewer);

}  // namespace app
