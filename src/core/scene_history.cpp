// The table of retired scene keys (scene_history.h). Add a row whenever a key is renamed or removed, and a
// test file of a run that used it (tests/fuzz/corpus/trajectory/ holds one of each trajectory version).
#include "core/scene_history.h"

namespace core {

const std::vector<RetiredKey>& retired_keys() {
  static const std::vector<RetiredKey> table = {
      {"arrest_speed", "0.1.0 (before the first release)", nullptr,
       "an arrest is judged by displacement now, not by an outlet speed: arrest_hold (s) and arrest_shift "
       "(radii) replaced it"},
  };
  return table;
}

const RetiredKey* find_retired(const std::string& key) {
  for (const RetiredKey& r : retired_keys())
    if (key == r.key) return &r;
  return nullptr;
}

}  // namespace core
