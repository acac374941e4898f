// Loading the module of picture and video readers (vision/codecs.h).
#include "vision/codecs.h"

#include <dlfcn.h>

#include <filesystem>

#include "core/error.h"

namespace vision {

namespace {
namespace fs = std::filesystem;

const Codecs* load() {
  std::error_code ec;
  const fs::path bin = fs::read_symlink("/proc/self/exe", ec).parent_path();
  std::string tried, why;
  for (const fs::path& dir : {bin / "lib" / "siloscope", bin / ".." / "lib" / "siloscope"}) {
    const fs::path module = dir / "siloscope_codecs.so";
    tried += (tried.empty() ? "" : " and ") + module.lexically_normal().string();
    if (!fs::exists(module, ec)) continue;
    void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      why = std::string(": ") + dlerror();
      continue;
    }
    using Entry = const Codecs* (*)();
    if (auto entry = reinterpret_cast<Entry>(dlsym(handle, "siloscope_codecs_v1"))) return entry();
    why = ": " + module.string() + " has no entry point siloscope_codecs_v1";
  }
  throw core::RuntimeFault(
      "siloscope's picture and video readers (siloscope_codecs.so) are not beside the "
      "binary: looked for " +
      tried + why + " (build with cmake, or install with cmake --install)");
}
}  // namespace

const Codecs& codecs() {
  static const Codecs* loaded = load();
  return *loaded;
}

}  // namespace vision
