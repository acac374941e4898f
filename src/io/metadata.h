// The metadata file every output directory carries: the version of siloscope, how it was invoked, every scene
// parameter (its [scene] table loads back as a scene file), and derived and measured facts of the run.
#pragma once

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/model.h"
#include "core/scene.h"

namespace io {

// One fact of a metadata file, typed where it is made: a string (written by the TOML library, every character
// escaped), a list of strings, a boolean, an integer, or a float (written with `digits` significant digits
// and always as a TOML float: 20 is "20.0", never an integer). The value's TOML text is made once, here.
class Fact {
 public:
  Fact(std::string key, const std::string& v);
  Fact(std::string key, const char* v) : Fact(std::move(key), std::string(v)) {}
  Fact(std::string key, const std::vector<std::string>& list);
  Fact(std::string key, bool v) : key_(std::move(key)), toml_(v ? "true" : "false") {}
  Fact(std::string key, double v, int digits = 9);
  template <class Int, std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, bool>, int> = 0>
  Fact(std::string key, Int v) : key_(std::move(key)), toml_(std::to_string(v)) {}
  const std::string& key() const { return key_; }
  const std::string& toml() const { return toml_; }  // the value as TOML text

 private:
  std::string key_, toml_;
};
using Facts = std::vector<Fact>;

struct RunInfo {
  std::string command;  // the command line
  Facts facts;          // written under [run]
  Facts health;         // written under [health]
  Facts look;           // written under [look]: how its pictures were drawn (a recording's)
};

// What a run's metadata says about its health and coverage (defaults when the tables or keys are absent).
struct RunRecord {
  long health_warnings = 0;      // --unsafe warnings (the run went on past a failed health check)
  bool ballistic = false;        // disks in flight above the column on average (kicks too strong)
  double airborne_fraction = 0;  // mean fraction of disks in flight
  bool interrupted = false;      // stopped before its planned duration
  double covered_s = -1;         // s of discharge the run covered (-1: the planned duration)
  // The drain protocol's outcome ("draining", "emptied", "jammed"; empty: not a drain), when, grains left.
  std::string drain_outcome;
  double drain_end_s = 0;
  long drain_remaining = 0;
  std::string command;  // the command line that made it ([siloscope] command)
};
// Throws core::InputError naming the file when it is not valid TOML.
RunRecord read_run_record(const std::string& metadata_path);
// The same from the metadata's text (`path` names it in errors).
RunRecord run_record_of(const std::string& text, const std::string& path);

std::string version_string();  // "0.1.0 (git abc1234, Release)"
std::string metadata_toml(const core::Model& model, const RunInfo& info);
// The first line of every metadata_toml text (how a file siloscope wrote is told from another).
inline constexpr const char* kMetadataFirstLine =
    "# siloscope run metadata: `siloscope run THIS_FILE` repeats the run.";

// Facts derived from the scene (counts, angles, the dipole's safe time step, ...), as [derived].
Facts derived_facts(const core::Model& model);

}  // namespace io
