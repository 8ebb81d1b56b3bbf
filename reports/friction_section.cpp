#include "reports/friction_section.hpp"

#include <filesystem>
#include <sstream>

#include "reports/html_parts.hpp"
#include "reports/plot.hpp"

namespace wr {
namespace {

using html::escape;
using html::fmt;

double num(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : NAN; }

PlotSeries curve_series(const nlohmann::json& curve, const std::string& label) {
  PlotSeries s{label, {}, {}, "linespoints", {}};
  for (const auto& p : curve["speeds"]) {
    s.x.push_back(num(p["v"]));
    s.y.push_back(num(p["mu"]));
  }
  return s;
}

}  // namespace

std::string friction_section_html(const std::string& file, const nlohmann::json& j, const std::string& chart_dir) {
  std::filesystem::create_directories(chart_dir);
  const auto& comp = j["compound"];
  const bool synthetic = comp.value("synthetic", false), wet = j.contains("wet");
  const bool flash = j.value("flash_temperature", false);
  std::ostringstream o;
  o << "<h2>Hysteresis friction against sliding speed: " << escape(file) << "</h2>\n"
    << "<p>Persson's theory (the rubber's viscoelastic loss excited by the road's asperities; the thesis's eq. 3.170), "
    << (flash ? "with" : "without") << " the flash temperature; compound <b>" << escape(comp.value("name", std::string("?")))
    << "</b>" << (synthetic ? " <span class=\"flag\">(SYNTHETIC: trends, not a prediction for a real tyre)</span>" : "")
    << "; &sigma;<sub>0</sub> " << fmt(num(j["pressure"])) << " Pa, T<sub>0</sub> " << fmt(num(j["temperature"]), "%.1f")
    << " &deg;C; spectrum from q<sub>0</sub> " << fmt(num(j["q0"])) << " to q<sub>1</sub> " << fmt(num(j["q1"]))
    << " 1/m, measured to " << fmt(num(j["q_measured"])) << " 1/m"
    << (j.value("extrapolated", false) ? " and <b>extrapolated</b> above along the fitted self-affine law" : "")
    << ".</p>\n";
  PlotSpec spec{"mu(v), " + std::string(flash ? "flash temperature" : "isothermal"), "sliding speed v [m/s]", "mu", true,
                false, {}};
  spec.series.push_back(curve_series(j, "dry"));
  if (wet) {
    const std::string cov = " (coverage " + std::to_string(static_cast<int>(100 * num(j["wet"]["coverage"]) + 0.5)) + " %)";
    spec.series.push_back(curve_series(j["wet"]["homogeneous"], "wet, homogeneous sealing" + cov));
    spec.series.push_back(curve_series(j["wet"]["local"], "wet, local sealing" + cov));
  }
  const std::string chart = chart_dir + "/mu_v.svg";
  write_svg_plot(chart, spec);
  o << html::figure(chart, "Hysteresis friction against sliding speed, dry and on the wet surface.");
  o << "<ul><li>dry: peak &mu; " << fmt(num(j["peak"]["mu"])) << " at " << fmt(num(j["peak"]["v"]), "%.3g")
    << " m/s; at 64 km/h &mu; " << fmt(num(j["locked_wheel"]["mu"])) << " (SN " << fmt(num(j["sn64"]), "%.1f")
    << "), flash temperature rise " << fmt(num(j["locked_wheel"]["temperature_rise"]), "%.1f") << " K</li>";
  if (wet)
    for (const char* m : {"homogeneous", "local"}) {
      const auto& c = j["wet"][m];
      o << "<li>wet, " << m << " sealing: peak &mu; " << fmt(num(c["peak"]["mu"])) << " at " << fmt(num(c["peak"]["v"]), "%.3g")
        << " m/s; at 64 km/h &mu; " << fmt(num(c["locked_wheel"]["mu"])) << " (SN " << fmt(num(c["sn64"]), "%.1f") << ")</li>";
    }
  o << "</ul>\n<table><tr><th>v [m/s]</th><th>&mu; dry</th><th>A/A0</th><th>&Delta;T [K]</th>"
    << (wet ? "<th>&mu; wet, homogeneous</th><th>&mu; wet, local</th>" : "") << "</tr>";
  for (std::size_t i = 0; i < j["speeds"].size(); ++i) {
    const auto& p = j["speeds"][i];
    o << "<tr><td>" << fmt(num(p["v"]), "%.3g") << "</td><td>" << fmt(num(p["mu"])) << "</td><td>"
      << fmt(num(p["area_fraction"]), "%.3g") << "</td><td>" << fmt(num(p["temperature_rise"]), "%.1f") << "</td>";
    if (wet)
      o << "<td>" << fmt(num(j["wet"]["homogeneous"]["speeds"][i]["mu"])) << "</td><td>"
        << fmt(num(j["wet"]["local"]["speeds"][i]["mu"])) << "</td>";
    o << "</tr>";
  }
  o << "</table>\n<p>Checks:</p><ul>";
  for (const auto& c : j["validity"]["checks"])
    o << "<li class=\"" << (c.value("passed", false) ? "ok" : "flag") << "\">" << escape(c.value("check", "")) << ": "
      << escape(c.value("detail", "")) << "</li>";
  o << "</ul>\n";
  return o.str();
}

}  // namespace wr
