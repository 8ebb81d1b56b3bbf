#pragma once
#include <string>

#include "roads/analyze.hpp"

namespace wr::app {

// Human-readable summary of an analysis: measured values, prescribed ones beside them.
std::string format_analysis(const AnalysisReport& r);

}  // namespace wr::app
