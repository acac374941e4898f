// "What if" (issue 56): a recorded run rebuilt at one of its frames from its metadata (runs are
// deterministic: the same steps give the same state bit for bit), checked against what was recorded, then
// changed (a grain removed, a kick now, a drive key) and continued; the inspector shows it beside the
// recorded run (ui/sources.h) and saves it as a run of its own.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "io/run.h"
#include "ui/sources.h"

namespace app {

class RunBrancher : public ui::Brancher {
 public:
  explicit RunBrancher(const io::Run& run) : run_(run) {}
  std::unique_ptr<ui::Branch> branch(long k) const override;

 private:
  const io::Run& run_;
};

}  // namespace app
