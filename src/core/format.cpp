#include "core/format.h"

#include <toml++/toml.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace core {

std::string toml_string(const std::string& s) {
  // Basic (double-quoted) strings only, whatever the content: metadata stays uniform to grep and diff.
  std::ostringstream o;
  const toml::value<std::string> v(s);
  o << toml::toml_formatter(v, toml::format_flags::allow_unicode_strings);
  return o.str();
}

std::string format_shortest(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  // Shortest text that reads back exactly.
  for (int prec = 1; prec < 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    // Exponents only for very small or large magnitudes: 20 prints as 20.0, not 2e+01.
    bool exponent = std::strchr(buf, 'e') != nullptr;
    bool tiny_or_huge = std::abs(v) < 1e-4 || std::abs(v) >= 1e16;
    if (std::strtod(buf, nullptr) == v && (!exponent || tiny_or_huge)) {
      s = buf;
      break;
    }
  }
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a TOML float
  return s;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace core
