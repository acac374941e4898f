// The history of scene keys: every key an earlier siloscope wrote that this one no longer reads, in one
// table.
//
// A run keeps its scene in metadata.toml (and a trajectory in its header); opening a run made before a key
// was renamed or removed must still work. A renamed key is translated to its new name; a removed key whose
// meaning no longer exists is dropped, and the scene says so (Scene::history). A scene file a person writes
// with a retired key is refused with the key that replaced it: its author meant something this version
// would not do.
#pragma once

#include <string>
#include <vector>

namespace core {

struct RetiredKey {
  const char* key;      // as an earlier siloscope wrote it
  const char* since;    // the version (or change) that retired it
  const char* renamed;  // its new name when only the name changed (the value carries over), else nullptr
  const char* why;      // what took its place, for a person
};

// Every retired key, oldest first.
const std::vector<RetiredKey>& retired_keys();
// The entry for `key`, or nullptr if it was never retired.
const RetiredKey* find_retired(const std::string& key);

}  // namespace core
