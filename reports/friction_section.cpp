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

// The wet friction at speed under the film: SN against speed, the skid number, Sp, FR60.
std::string film_html(const nlohmann::json& f, const std::string& chart_dir) {
  std::ostringstream o;
  o << "<h3>Skid numbers at speed under a " << fmt(1e3 * num(f["water_film"]), "%.3g") << " mm water film (test "
    << escape(f.value("test", std::string("?"))) << ")</h3>\n"
    << "<p>A road element spends the time L<sub>c</sub>/v = " << fmt(num(f["patch_length"]), "%.3g")
    << " m / v under the sliding tread; the film drains across the drainage length " << fmt(1e3 * num(f["drainage_length"]), "%.3g")
    << " mm through the texture (Lorenz &amp; Persson's squeeze-out with Persson's load-separation and the effective-medium "
       "flow conductance); the asperities' share of the load slides with the hysteresis friction, the water's is sheared "
       "as a film. Source of the test's values: "
    << escape(f.value("source", std::string("?"))) << ".</p>\n";
  PlotSpec spec{"skid number against speed", "speed [km/h]", "SN = 100 mu", false, false, {}};
  PlotSeries wet{"under the film", {}, {}, "linespoints", {}}, drained{"drained road (hysteresis alone)", {}, {}, "lines", {}};
  for (const auto& p : f["skid"]) {
    wet.x.push_back(3.6 * num(p["v"]));
    wet.y.push_back(100 * num(p["mu"]));
    drained.x.push_back(3.6 * num(p["v"]));
    drained.y.push_back(100 * num(p["mu_hysteresis"]));
  }
  spec.series = {wet, drained};
  const std::string chart = chart_dir + "/sn_speed.svg";
  write_svg_plot(chart, spec);
  o << html::figure(chart, "Skid number against speed under the film, and the drained road's hysteresis friction.");
  const auto& t = f["at_test"];
  o << "<ul><li><b>skid number at " << fmt(3.6 * num(f["slip_speed"]), "%.0f") << " km/h: SN " << fmt(num(f["sn"]), "%.1f")
    << "</b> (asperities carry " << fmt(100 * num(t["load_share"]), "%.1f") << " % of the load over the patch; "
    << (t["drain_time"].is_null() ? std::string("the film never drains to 90 %")
                                  : "the film drains to 90 % load share in " + fmt(1e3 * num(t["drain_time"]), "%.3g") + " ms")
    << " against " << fmt(1e3 * num(t["patch_time"]), "%.3g") << " ms under the tyre)</li>"
    << "<li>speed constant Sp "
    << (f["sp_kmh"].is_null() ? std::string("none (friction does not fall with speed)") : fmt(num(f["sp_kmh"]), "%.1f") + " km/h")
    << " (ASTM E1960's exponential fitted over 20&ndash;100 km/h); FR60 " << fmt(num(f["fr60"]), "%.3f") << "</li>"
    << "<li>hydroplaning: "
    << (f["hydroplaning_kmh"].is_null() ? std::string("none at any speed (the texture holds or drains the film)")
                                        : "above " + fmt(num(f["hydroplaning_kmh"]), "%.0f") + " km/h")
    << "</li></ul>\n";
  if (f.contains("band")) {
    const auto& b = f["band"];
    o << "<p><b>Band of the skid number</b> over the inputs' ranges (Latin hypercube, " << b["samples"].get<int>()
      << " samples): 5&ndash;95 % " << fmt(num(b["p05"]), "%.1f") << " &ndash; " << fmt(num(b["p95"]), "%.1f")
      << ", extremes " << fmt(num(b["min"]), "%.1f") << " &ndash; " << fmt(num(b["max"]), "%.1f")
      << ". The tornado: each input alone at the ends of its range, the others nominal.</p>\n";
    // the tornado: one horizontal bar per input, the largest swing on top
    PlotSpec t{"tornado: SN at 64 km/h, one input at a time", "SN", "input (largest swing on top)", false, false, {}};
    const auto& rows = b["tornado"];
    const double n = static_cast<double>(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& r = rows[i];
      const double y = n - static_cast<double>(i);
      t.series.push_back({r.value("name", std::string("?")) + " " + fmt(num(r["low"]), "%.3g") + " ... " + fmt(num(r["high"]), "%.3g"),
                          {num(r["sn_low"]), num(r["sn_high"])}, {y, y}, "linespoints", {}});
    }
    t.series.push_back({"nominal", {num(b["nominal"]), num(b["nominal"])}, {0.5, n + 0.5}, "lines", {}});
    t.key = "outside right";
    const std::string chart = chart_dir + "/tornado.svg";
    write_svg_plot(chart, t);
    o << html::figure(chart, "Tornado chart of the skid number: the swing each input causes over its range.");
  }
  return o.str();
}

}  // namespace

// The exact rung's run: its curve beside Persson's theory on the same band, and the ladder's speed
// against accuracy on this surface (Persson's deviation from the exact answer at each speed; the
// exact rung's own error indicator, the dissipation identity's residual).
std::string exact_rung_html(const nlohmann::json& j, const std::string& chart_dir) {
  const auto& e = j["exact"];
  const auto& pe = e["persson_same_band"];
  std::ostringstream o;
  o << "<h3>The exact rung: steady viscoelastic sliding on the map</h3>\n<p>Chosen: " << escape(j.value("rung_chosen_by", ""))
    << ". The rubber's steady sliding over the map itself (FFT boundary elements with the complex modulus, "
    << e["grid"][0].get<std::size_t>() << "&times;" << e["grid"][1].get<std::size_t>() << " grid, the map's band to "
    << fmt(num(e["q_band"]), "%.4g") << " 1/m), beside Persson's theory on the same band. "
    << (e.value("converged", false) ? "Converged at every speed" : "<span class=\"flag\">NOT converged: " + escape(e.value("message", "")) + "</span>")
    << "; dissipation identity within " << fmt(num(e["max_identity_residual"]), "%.2g") << ".</p>\n";
  PlotSpec ladder{"speed against accuracy of the friction ladder on this surface", "wall time per speed [s]",
                  "relative deviation from the exact rung", true, true, {}};
  double persson_time = 0;
  for (const auto& [phase, t] : j["timings"].items())
    if (phase.find("Persson on the same band") != std::string::npos) persson_time = num(t.is_object() ? t["wall_s"] : t);
  const double speeds = double(j["speeds"].size() + 1);
  PlotSeries ps{"Persson's theory, each speed", {}, {}, "points", {}};
  for (std::size_t i = 0; i < j["speeds"].size(); ++i) {
    const double mu = num(j["speeds"][i]["mu"]), mp = num(pe["speeds"][i]["mu"]);
    if (mu > 0 && mp != mu) ps.x.push_back(std::max(persson_time / speeds, 1e-6)), ps.y.push_back(std::abs(mp / mu - 1));
  }
  const double solves = std::max(1.0, num(e["solves"]));
  PlotSeries ex{"exact rung (its dissipation-identity residual)", {num(e["wall_s"]) / solves},
                {std::max(num(e["max_identity_residual"]), 1e-6)}, "points pt 7 ps 2", {}};
  ladder.series = {ps, ex};
  ladder.key = "top right";
  const std::string chart = chart_dir + "/friction_ladder.svg";
  write_svg_plot(chart, ladder);
  o << html::figure(chart, "Time per speed against accuracy: Persson's theory's deviation from the exact answer at each speed, "
                           "and the exact rung's own error indicator.");
  return o.str();
}

std::string friction_section_html(const std::string& file, const nlohmann::json& j, const std::string& chart_dir) {
  std::filesystem::create_directories(chart_dir);
  const auto& comp = j["compound"];
  const bool synthetic = comp.value("synthetic", false), wet = j.contains("wet");
  const bool flash = j.value("flash_temperature", false);
  std::ostringstream o;
  const bool exact = j.value("rung", std::string("persson")) == "viscoelastic" && j.contains("exact");
  o << "<h2>Hysteresis friction against sliding speed: " << escape(file) << "</h2>\n<p>"
    << (exact ? "Exact steady sliding of the rubber over the map (its viscoelastic loss excited by the road's asperities), "
                "Persson's theory on the same band beside it; isothermal"
              : std::string("Persson's theory (the rubber's viscoelastic loss excited by the road's asperities; the thesis's "
                            "eq. 3.170), ") + (flash ? "with" : "without") + " the flash temperature")
    << "; compound <b>" << escape(comp.value("name", std::string("?")))
    << "</b>" << (synthetic ? " <span class=\"flag\">(SYNTHETIC: trends, not a prediction for a real tyre)</span>" : "")
    << "; &sigma;<sub>0</sub> " << fmt(num(j["pressure"])) << " Pa, T<sub>0</sub> " << fmt(num(j["temperature"]), "%.1f")
    << " &deg;C; spectrum from q<sub>0</sub> " << fmt(num(j["q0"])) << " to q<sub>1</sub> " << fmt(num(j["q1"]))
    << " 1/m, measured to " << fmt(num(j["q_measured"])) << " 1/m"
    << (j.value("extrapolated", false) ? " and <b>extrapolated</b> above along the fitted self-affine law" : "")
    << ".</p>\n";
  PlotSpec spec{"mu(v), " + std::string(flash ? "flash temperature" : "isothermal"), "sliding speed v [m/s]", "mu", true,
                false, {}};
  spec.series.push_back(curve_series(j, exact ? "dry, exact steady sliding on the map" : "dry"));
  if (exact) spec.series.push_back(curve_series(j["exact"]["persson_same_band"], "dry, Persson on the same band"));
  if (wet && exact) {
    const std::string cov = " (coverage " + std::to_string(static_cast<int>(100 * num(j["wet"]["coverage"]) + 0.5)) + " %)";
    spec.series.push_back(curve_series(j["wet"]["homogeneous"], "wet, sealed pools as flat walls, exact" + cov));
  } else if (wet) {
    const std::string cov = " (coverage " + std::to_string(static_cast<int>(100 * num(j["wet"]["coverage"]) + 0.5)) + " %)";
    spec.series.push_back(curve_series(j["wet"]["homogeneous"], "wet, homogeneous sealing" + cov));
    spec.series.push_back(curve_series(j["wet"]["local"], "wet, local sealing" + cov));
  }
  const std::string chart = chart_dir + "/mu_v.svg";
  write_svg_plot(chart, spec);
  o << html::figure(chart, "Hysteresis friction against sliding speed, dry and on the wet surface.");
  o << "<ul><li>dry: peak &mu; " << fmt(num(j["peak"]["mu"])) << " at " << fmt(num(j["peak"]["v"]), "%.3g")
    << " m/s; at 64 km/h &mu; " << fmt(num(j["locked_wheel"]["mu"]))
    << " (a dry road has no skid number), flash temperature rise " << fmt(num(j["locked_wheel"]["temperature_rise"]), "%.1f") << " K</li>";
  if (wet)
    for (const char* m : {"homogeneous", "local"}) {
      const auto& c = j["wet"][m];
      o << "<li>wet, " << m << " sealing: peak &mu; " << fmt(num(c["peak"]["mu"])) << " at " << fmt(num(c["peak"]["v"]), "%.3g")
        << " m/s; at 64 km/h &mu; " << fmt(num(c["locked_wheel"]["mu"])) << " (pools sealed, no film)</li>";
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
  o << "</table>\n";
  if (exact) o << exact_rung_html(j, chart_dir);
  if (j.contains("q1_scan") && !j["q1_scan"].empty()) {
    // mu against the cut-off, with the run's own q1 (a number, the default, or a criterion's) marked
    PlotSpec q{"dry mu at 64 km/h against the cut-off q1", "q1 [1/m]", "mu", true, false, {}};
    PlotSeries scan{"mu(q1)", {}, {}, "linespoints", {}};
    for (const auto& p : j["q1_scan"]) scan.x.push_back(num(p["q1"])), scan.y.push_back(num(p["mu_locked_wheel"]));
    const std::string choice = j.value("q1_choice", std::string("default"));
    PlotSeries chosen{"this run's q1 (" + choice + ")", {num(j["q1"])}, {num(j["locked_wheel"]["mu"])}, "points pt 7 ps 2", {}};
    q.series = {scan, chosen};
    const std::string chart = chart_dir + "/mu_q1.svg";
    write_svg_plot(chart, q);
    o << html::figure(chart, "The unmeasured scales: mu at 64 km/h against the cut-off q1, this run's choice marked (" +
                                 escape(choice) + ", q1 = " + fmt(num(j["q1"]), "%.3g") + " 1/m).");
  }
  if (j.contains("water_film")) o << film_html(j["water_film"], chart_dir);
  o << "<p>Checks:</p><ul>";
  for (const auto& c : j["validity"]["checks"])
    o << "<li class=\"" << (c.value("passed", false) ? "ok" : "flag") << "\">" << escape(c.value("check", "")) << ": "
      << escape(c.value("detail", "")) << "</li>";
  o << "</ul>\n";
  return o.str();
}

}  // namespace wr
