#include "reports/html_parts.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "lib/core/utf8.hpp"

namespace wr::html {
namespace {

// The SVG text of a chart written by gnuplot, without its XML prolog, for inline embedding.
std::string inline_svg(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  std::string t = s.str();
  const auto at = t.find("<svg");
  if (at == std::string::npos) throw std::runtime_error(file + ": not an SVG chart");
  return t.substr(at);
}

}  // namespace

std::string figure(const std::string& svg_file, const std::string& caption) {
  return "<figure>" + inline_svg(svg_file) + "<figcaption>" + caption + "</figcaption></figure>\n";
}

std::string escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    char32_t cp = 0;
    const std::size_t n = utf8_length_at(s, i, &cp);
    if (n == 0) {  // not UTF-8 (latin-1 from an old file): the page is UTF-8, so U+FFFD per byte
      o += "&#xFFFD;";
      ++i;
      continue;
    }
    if (cp == '<') o += "&lt;";
    else if (cp == '>') o += "&gt;";
    else if (cp == '&') o += "&amp;";
    else if (cp == '"') o += "&quot;";
    else if (cp == '\'') o += "&#39;";
    else if (cp == '\t' || cp == '\n') o += static_cast<char>(cp);
    // NUL and the other controls have no character reference a browser shows (&#0; and C1
    // references are parse errors): the replacement character marks where one was.
    else if (is_control(cp)) o += "&#xFFFD;";
    else o.append(s, i, n);
    i += n;
  }
  return o;
}

std::string fmt(double v, const char* f) {
  if (!std::isfinite(v)) return "&ndash;";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace wr::html
