#pragma once
// Plain-text numeric files (height grids, point clouds): one record per line, fields separated
// by whitespace, commas, semicolons or tabs; blank lines and lines starting with '#' skipped.
#include <cstdlib>
#include <istream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace wr {

// The next record's fields; false at the end of the input. `lineno` counts every line read
// (for messages naming the line).
inline bool next_text_record(std::istream& in, std::vector<std::string>& fields, std::size_t& lineno) {
  std::string line;
  while (std::getline(in, line)) {
    ++lineno;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::istringstream ls(line);
    fields.clear();
    for (std::string tok; ls >> tok;) fields.push_back(tok);
    return true;
  }
  return false;
}

// The whole token as a number (strtod: also nan, inf), or nullopt.
inline std::optional<double> parse_number(const std::string& tok) {
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0') return std::nullopt;
  return v;
}

}  // namespace wr
