#pragma once
// The report's hysteresis-friction section: for each result of `wetroad friction --out`, the
// mu(v) curves dry and wet (homogeneous and local sealing) as a chart and a table, the peak,
// mu at 64 km/h, the model's validity checks and where the numbers come from.
#include <string>

#include <nlohmann/json.hpp>

namespace wr {

// `summary`: read_friction_summary(file). Charts go into `chart_dir`.
std::string friction_section_html(const std::string& file, const nlohmann::json& summary, const std::string& chart_dir);

}  // namespace wr
