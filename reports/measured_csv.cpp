#include "reports/measured_csv.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "lib/core/errors.hpp"
#include "lib/core/utf8.hpp"
#include "lib/io/input_file.hpp"

namespace wr {
namespace {

struct CsvField {
  std::string text;
  std::size_t line = 0, column = 0;  // where the field starts, both from 1
  bool quoted = false;
};

// RFC 4180 records from the whole text. Line numbers count every line end, those inside quoted
// fields included, so that a message names the line an editor shows.
class CsvRecords {
 public:
  CsvRecords(const std::string& text, const std::string& source) : s_(text), source_(source) {
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = line_start_ = 3;  // UTF-8 BOM (Excel's "CSV UTF-8")
  }

  // The next record's fields; false at the end of the text.
  bool next(std::vector<CsvField>& rec) {
    rec.clear();
    if (i_ >= s_.size()) return false;
    for (;;) {
      skip_blanks();
      CsvField f;
      f.line = line_;
      f.column = column_at(i_);
      if (i_ < s_.size() && s_[i_] == '"') {
        read_quoted(f);
      } else {
        const std::size_t b = i_;
        while (i_ < s_.size() && s_[i_] != ',' && s_[i_] != '\r' && s_[i_] != '\n') {
          if (s_[i_] == '"')
            fail(line_, column_at(i_), "a quote inside an unquoted field (quote the whole field, and double the quotes in it: \"a \"\"b\"\"\")");
          ++i_;
        }
        std::size_t e = i_;
        while (e > b && (s_[e - 1] == ' ' || s_[e - 1] == '\t')) --e;
        f.text.assign(s_, b, e - b);
      }
      rec.push_back(std::move(f));
      if (i_ < s_.size() && s_[i_] == ',') {
        ++i_;
        continue;
      }
      line_end();
      return true;
    }
  }

  [[noreturn]] void fail(std::size_t line, std::size_t column, const std::string& what) const {
    throw InputError(source_, "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what);
  }

 private:
  void skip_blanks() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }

  // Consumes one line end (CRLF, LF or a lone CR) at i_, if there is one.
  bool line_end() {
    if (i_ >= s_.size()) return false;
    if (s_[i_] == '\r') {
      ++i_;
      if (i_ < s_.size() && s_[i_] == '\n') ++i_;
    } else if (s_[i_] == '\n') {
      ++i_;
    } else {
      return false;
    }
    ++line_;
    line_start_ = i_;
    return true;
  }

  void read_quoted(CsvField& f) {
    f.quoted = true;
    ++i_;  // the opening quote
    for (;;) {
      if (i_ >= s_.size())
        fail(f.line, f.column, "this quoted field is never closed (a quote inside a quoted field is doubled: \"\")");
      const char c = s_[i_];
      if (c == '"') {
        if (i_ + 1 < s_.size() && s_[i_ + 1] == '"') {
          f.text += '"';
          i_ += 2;
          continue;
        }
        ++i_;
        break;
      }
      if (c == '\r' || c == '\n') {  // a line break inside the field is part of it
        const std::size_t b = i_;
        line_end();
        f.text.append(s_, b, i_ - b);
        continue;
      }
      f.text += c;
      ++i_;
    }
    skip_blanks();
    if (i_ < s_.size() && s_[i_] != ',' && s_[i_] != '\r' && s_[i_] != '\n')
      fail(line_, column_at(i_), "text after a field's closing quote (a quote inside a quoted field is doubled: \"\")");
  }

  // Characters (UTF-8 code points; other bytes one each) from the line's start, from 1.
  std::size_t column_at(std::size_t pos) const {
    std::size_t col = 1;
    for (std::size_t k = line_start_; k < pos; ++k)
      if ((static_cast<unsigned char>(s_[k]) & 0xC0) != 0x80) ++col;
    return col;
  }

  const std::string& s_;
  const std::string& source_;
  std::size_t i_ = 0, line_ = 1, line_start_ = 0;
};

const char* const kColumns[] = {"site", "mpd_mm", "sn40r", "speed_kmh"};

std::string where(const CsvField& f) {
  return "line " + std::to_string(f.line) + ", column " + std::to_string(f.column);
}

// A field's text on one line of a message: control bytes as \xNN, at most 40 bytes.
std::string shown(const std::string& t) {
  std::string s;
  for (std::size_t i = 0; i < t.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(t[i]);
    char b[8];
    std::snprintf(b, sizeof b, "\\x%02x", c);
    s += c < 0x20 || c == 0x7f ? std::string(b) : std::string(1, t[i]);
  }
  return t.size() > 40 ? s + "..." : s;
}

double value(const CsvField& f, const std::string& source, const char* what, double lo, double hi) {
  char* end = nullptr;
  const double v = f.text.empty() ? 0 : std::strtod(f.text.c_str(), &end);
  // The whole field, its size and not its first NUL: "0.9\0" "5" is not 0.9.
  if (f.text.empty() || end != f.text.c_str() + f.text.size() || !(v >= lo && v <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
    throw InputError(source, where(f) + " (" + what + "): '" + shown(f.text) + "' is not a number in " + range);
  }
  return v;
}

// The site name as the report will show it: well-formed UTF-8 without control characters.
void check_site(const CsvField& f, const std::string& source) {
  const std::size_t line = f.line;
  std::size_t col = f.column + (f.quoted ? 1 : 0);  // a control character ends the check before a line break
  for (std::size_t i = 0; i < f.text.size();) {
    char32_t cp = 0;
    const std::size_t n = utf8_length_at(f.text, i, &cp);
    char b[96];
    if (n == 0) {
      std::snprintf(b, sizeof b, "byte 0x%02X", static_cast<unsigned char>(f.text[i]));
      throw InputError(source, "line " + std::to_string(line) + ", column " + std::to_string(col) + " (site): " + b +
                                   " is not UTF-8 (a latin-1 or Windows-1252 file? save it as UTF-8)");
    }
    if (is_control(cp)) {
      std::snprintf(b, sizeof b, "U+%04X", static_cast<unsigned>(cp));
      throw InputError(source, "line " + std::to_string(line) + ", column " + std::to_string(col) + " (site): " +
                                   "a control character (" + b + ") in a site name");
    }
    i += n;
    ++col;
  }
}

}  // namespace

std::vector<MeasuredSkid> parse_measured_skid_csv(const std::string& text, const std::string& source) {
  CsvRecords csv(text, source);
  std::vector<CsvField> head;
  if (!csv.next(head)) throw InputError(source, "empty file (expected the header site,mpd_mm,sn40r[,speed_kmh])");
  for (std::size_t k = 0; k < head.size() || k < 3; ++k)
    if (k == head.size() || k == 4 || head[k].text != kColumns[k])
      throw InputError(source, where(head[std::min(k, head.size() - 1)]) + ": the header must be site,mpd_mm,sn40r[,speed_kmh]" +
                                   (k < head.size() && k < 4 ? " (field " + std::to_string(k + 1) + " is '" + shown(head[k].text) + "')" : ""));
  std::vector<MeasuredSkid> out;
  std::vector<CsvField> f;
  while (csv.next(f)) {
    if (f.size() == 1 && f[0].text.empty()) continue;  // a blank line
    if (f.size() > head.size())
      throw InputError(source, where(f[head.size()]) + ": field " + std::to_string(head.size() + 1) + "; the header has " +
                                   std::to_string(head.size()) + " (a site name with a comma goes in quotes: \"a, b\")");
    if (f.size() < head.size())
      throw InputError(source, where(f.back()) + ": the record ends after " + std::to_string(f.size()) +
                                   " fields; the header has " + std::to_string(head.size()));
    MeasuredSkid m;
    check_site(f[0], source);
    m.site = f[0].text;
    m.mpd_mm = value(f[1], source, "mpd_mm", 0, 10);
    m.sn40r = value(f[2], source, "sn40r", 0, 150);
    if (f.size() > 3 && !f[3].text.empty()) m.speed_kmh = value(f[3], source, "speed_kmh", 1, 300);
    out.push_back(m);
  }
  if (out.empty()) throw InputError(source, "no data rows");
  return out;
}

std::vector<MeasuredSkid> read_measured_skid_csv(const std::string& path) {
  return parse_measured_skid_csv(read_input_file(path, "measured skid-number CSV"), path);
}

}  // namespace wr
