#include "reports/html_parts.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

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
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
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
