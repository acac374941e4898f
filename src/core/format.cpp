#include "core/format.h"

#include <toml++/toml.h>

#include <sstream>

namespace core {

std::string toml_string(const std::string& s) {
  // Basic (double-quoted) strings only, whatever the content: metadata stays uniform to grep and diff.
  std::ostringstream o;
  const toml::value<std::string> v(s);
  o << toml::toml_formatter(v, toml::format_flags::allow_unicode_strings);
  return o.str();
}

}  // namespace core
