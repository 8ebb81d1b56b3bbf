#pragma once
// Small HTML helpers shared by the report's sections (reports/html_report.cpp,
// reports/friction_section.cpp).
#include <string>

namespace wr::html {

std::string escape(const std::string& s);  // & < > " as entities
// `v` printed with the printf format `f` (one conversion); an en dash when not finite.
std::string fmt(double v, const char* f = "%.4g");
// A <figure> with the SVG chart in `svg_file` inlined (its XML prolog dropped) and a caption.
std::string figure(const std::string& svg_file, const std::string& caption);

}  // namespace wr::html
