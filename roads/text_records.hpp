#pragma once
// Plain-text numeric files (height grids, point clouds): one record per line, fields separated
// by whitespace, commas, semicolons or tabs; blank lines and lines starting with '#' skipped.
//
// A reader either reads exactly what is there or refuses naming the line and column, so:
// - "\n", "\r\n" and a lone "\r" (old Mac OS) each end one line: a CR-only grid read as one
//   line would be a 1-D profile of the whole map, with exit 0;
// - a UTF-8 byte order mark at the start of the file is skipped (editors on Windows write one;
//   left in, it makes the first number unreadable);
// - a number is the whole token: a NUL byte or any other character after the digits refuses the
//   token (strtod on c_str() would stop at the NUL and read the digits before it).
#include <cstddef>
#include <cstdlib>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace wr {

// The whole token as a number (strtod: also nan, inf), or nullopt.
inline std::optional<double> parse_number(const std::string& tok) {
  if (tok.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (end != tok.c_str() + tok.size()) return std::nullopt;  // size(), not '\0': a NUL inside is refused
  return v;
}

// A token as an error message shows it: on one line (control bytes as \xNN) and at most 40 bytes.
inline std::string shown_token(const std::string& tok) {
  static const char* hex = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < tok.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(tok[i]);
    if (c < 0x20 || c == 0x7f) s += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    else s += static_cast<char>(c);
  }
  if (tok.size() > 40) s += "...";
  return s;
}

// Splits a text stream into records of fields, keeping where each field starts.
class TextRecords {
 public:
  explicit TextRecords(std::istream& in) : in_(in) {}

  // The next non-blank, non-comment record; false at the end of the input.
  bool next() {
    std::string line;
    while (next_line(line)) {
      const auto first = line.find_first_not_of(" \t\v\f");
      if (first == std::string::npos || line[first] == '#') continue;
      line_ = std::move(line);
      fields_.clear();
      starts_.clear();
      std::size_t i = 0;
      while (i < line_.size()) {
        while (i < line_.size() && is_separator(line_[i])) ++i;
        if (i == line_.size()) break;
        const std::size_t b = i;
        while (i < line_.size() && !is_separator(line_[i])) ++i;
        fields_.emplace_back(line_, b, i - b);
        starts_.push_back(b);
      }
      return true;
    }
    return false;
  }

  // Empty for a line of separators only (",,,"): not blank, and no values either; the caller
  // refuses it (where() needs a field).
  const std::vector<std::string>& fields() const { return fields_; }
  std::size_t line() const { return lineno_; }  // 1-based number of the current record's line
  // "line L, column C (field F)": C counts characters (UTF-8 code points) from 1, F fields from 1.
  std::string where(std::size_t field) const {
    std::size_t col = 1;
    for (std::size_t k = 0; k < starts_[field]; ++k)
      if ((static_cast<unsigned char>(line_[k]) & 0xC0) != 0x80) ++col;
    return "line " + std::to_string(lineno_) + ", column " + std::to_string(col) + " (field " +
           std::to_string(field + 1) + ")";
  }

 private:
  static bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\v' || c == '\f'; }

  // One line whatever its end: getline splits at '\n', and a chunk is split again at each '\r'
  // (a '\r' just before the '\n' ends the same line, not an extra empty one).
  bool next_line(std::string& line) {
    if (pos_ == std::string::npos) {
      if (!std::getline(in_, chunk_)) return false;
      pos_ = 0;
      if (lineno_ == 0 && chunk_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // UTF-8 BOM
    }
    const std::size_t cr = chunk_.find('\r', pos_);
    if (cr == std::string::npos) {
      line.assign(chunk_, pos_, std::string::npos);
      pos_ = std::string::npos;
    } else {
      line.assign(chunk_, pos_, cr - pos_);
      pos_ = cr + 1 == chunk_.size() ? std::string::npos : cr + 1;
    }
    ++lineno_;
    return true;
  }

  std::istream& in_;
  std::string chunk_, line_;
  std::size_t pos_ = std::string::npos, lineno_ = 0;
  std::vector<std::string> fields_;
  std::vector<std::size_t> starts_;
};

}  // namespace wr
