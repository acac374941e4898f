// Numbers as text for CSV, TOML and messages: one formatter instead of one per file.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace core {

// printf("%.{digits}g"), with NaN always written "nan".
inline std::string format_g(double v, int digits = 9) {
  if (std::isnan(v)) return "nan";
  char b[48];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

// "a run", "an analysis": the indefinite article a message needs before `noun`.
inline std::string with_article(const std::string& noun) {
  const bool vowel = !noun.empty() && std::string("aeiouAEIOU").find(noun[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + noun;
}

// The same, kept a TOML float: "20" becomes "20.0".
inline std::string format_toml_float(double v, int digits = 9) {
  std::string s = format_g(v, digits);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// The shortest text that reads back as exactly v, kept a TOML float ("20.0", "0.065", "5e-05"): scene files
// and messages that quote a value the user wrote.
std::string format_shortest(double v);

// A TOML basic string with every character escaped as TOML requires (quotes, backslashes, control
// characters), written by the TOML library: any path or command line round-trips through metadata.toml.
std::string toml_string(const std::string& s);

// A string quoted for /bin/sh.
inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A file name's extension in lower case, with its dot (".h5" for "Tracks.H5"; "" for none).
std::string lower_extension(const std::string& path);

}  // namespace core
