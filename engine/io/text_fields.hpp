#pragma once
// Reading whitespace-separated fields of one line of a data file (Matrix
// Market, profile CSV).
#include <sstream>
#include <string>

namespace railvsi {

// Parses exactly the given values from `line`: false on missing, malformed
// (including "nan" and "inf") or extra fields.
template <class... T>
bool parse_fields(const std::string& line, T&... values) {
  std::istringstream ss(line);
  if (!(ss >> ... >> values)) return false;
  ss >> std::ws;
  return ss.eof();
}

}  // namespace railvsi
