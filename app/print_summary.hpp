#pragma once
#include <string>

#include "roads/analyze.hpp"
#include "roads/surface_import.hpp"

namespace wr::app {

// Human-readable summary of an analysis: measured values, prescribed ones beside them.
std::string format_analysis(const AnalysisReport& r);

// The loader's warnings on stderr, one line each: "wetroad: warning: FILE: ...".
void print_load_warnings(const LoadedSurface& s);
// "read FILE" and describe_import's line, on stdout (not under -q: it is a report, not a warning).
void print_import(const LoadedSurface& s);

}  // namespace wr::app
