#pragma once
// Small HTML helpers shared by the report's sections (reports/html_report.cpp,
// reports/friction_section.cpp).
#include <string>

namespace wr::html {

// Text as HTML content or attribute value: & < > " ' as entities; controls other than tab and
// newline, and bytes that are not UTF-8, as U+FFFD (the page is UTF-8 and must stay so).
std::string escape(const std::string& s);
// `v` printed with the printf format `f` (one conversion); an en dash when not finite.
std::string fmt(double v, const char* f = "%.4g");
// A <figure> with the SVG chart in `svg_file` inlined (its XML prolog dropped) and a caption.
std::string figure(const std::string& svg_file, const std::string& caption);

}  // namespace wr::html
