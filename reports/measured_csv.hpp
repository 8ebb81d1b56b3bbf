#pragma once
// The measured skid numbers of `wetroad report --measured`: a CSV with the header
// `site,mpd_mm,sn40r[,speed_kmh]`, read per RFC 4180 as spreadsheets write it: fields in double
// quotes may hold commas, line breaks and quotes (doubled: ""), records end in CRLF, LF or CR,
// a UTF-8 byte order mark before the header is skipped, blank lines are skipped, and blanks
// around a field are not part of it.
//
// Site names go into the HTML report: each must be UTF-8 without control characters (a
// latin-1 file is refused naming the line and column of the first byte that is not UTF-8, so
// that the user re-saves it as UTF-8 rather than getting a page of replacement characters).
#include <optional>
#include <string>
#include <vector>

namespace wr {

struct MeasuredSkid {
  std::string site;
  double mpd_mm = 0, sn40r = 0;
  std::optional<double> speed_kmh;  // test speed (default 64 km/h = 40 mph)
};

// Throws InputError(path, "line L, column C ...: ...") for a malformed record (an unclosed
// quote, a quote inside an unquoted field, a wrong number of fields), a missing column, a
// non-numeric or out-of-range value, or a site name that is not UTF-8 text.
std::vector<MeasuredSkid> read_measured_skid_csv(const std::string& path);
// The same on the file's bytes (`source` names it in messages).
std::vector<MeasuredSkid> parse_measured_skid_csv(const std::string& text, const std::string& source);

}  // namespace wr
