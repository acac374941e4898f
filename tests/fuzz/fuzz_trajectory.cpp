// libFuzzer target: the trajectory reader must refuse corrupted, truncated and foreign bytes cleanly.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "io/trajectory.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    io::Trajectory t(std::vector<unsigned char>(data, data + size), "fuzz.sstraj");
    for (long k = 0; k < t.size() && k < 3; ++k) (void)t.frame(k), (void)t.time(k);
  } catch (const core::InputError&) {
  }
  return 0;
}
