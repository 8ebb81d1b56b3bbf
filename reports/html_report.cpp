#include "reports/html_report.hpp"

#include "lib/core/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "lib/core/errors.hpp"
#include "lib/core/least_squares.hpp"
#include "lib/core/provenance.hpp"
#include "lib/io/atomic_output.hpp"
#include "reports/friction_section.hpp"
#include "reports/html_parts.hpp"
#include "reports/sweep_outputs.hpp"
#include "reports/plot.hpp"
#include "reports/skid_speed_section.hpp"
#include "reports/summary_section.hpp"
#include "wetroad/version.hpp"

namespace wr {
namespace {

using html::escape;
using html::figure;
using html::fmt;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSkidSpeed = 64.0;  // km/h: SN40R is measured at 40 mph

double num(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : kNaN; }

std::string validity_section(const std::string& file, const nlohmann::json& sweep) {
  std::ostringstream o;
  int invalid = 0;
  std::string checks;
  for (const auto& r : sweep["runs"]) {
    if (!r.contains("contact")) continue;
    const auto& v = r["contact"]["validity"];
    if (!v.is_object() || v.value("valid", true)) continue;
    ++invalid;
    if (checks.empty())
      for (const auto& c : v["checks"])
        if (!c.value("passed", true))
          checks += "<li>" + escape(c.value("check", "")) + ": " + escape(c.value("detail", "")) + "</li>";
  }
  if (invalid > 0)
    o << "<p class=\"flag\">Outside the model's validity: " << invalid << " of " << sweep["runs"].size()
      << " runs of " << escape(file) << ". Failed checks (first such run):</p><ul>" << checks << "</ul>\n";
  else
    o << "<p class=\"ok\">Every run of " << escape(file) << " passed its model's validity checks.</p>\n";
  if (sweep.value("failed_runs", 0) > 0)
    o << "<p class=\"flag\">" << sweep["failed_runs"].get<int>()
      << " runs failed (water target unreachable or contact not converged); they are listed below and left out of "
         "the means.</p>\n";
  return o.str();
}

// The HDF5 group of run `index` (reports/sweep_outputs.hpp).
std::string run_group(int index) {
  char b[32];
  std::snprintf(b, sizeof b, "/runs/run-%04d", index);
  return b;
}

// The source column of a table row: its runs' HDF5 groups.
std::string run_groups(const nlohmann::json& indices) {
  std::string out;
  for (const auto& i : indices) {
    if (!out.empty()) out += ' ';
    out += run_group(i.get<int>());
  }
  return out;
}

std::string coverage_table_html(const std::string& file, const nlohmann::json& sweep) {
  std::ostringstream o;
  o << "<table><tr><th>target</th><th>water</th><th>coverage</th><th>&mu; peak</th><th>&mu;<sub>wet</sub>/&mu;<sub>dry</sub></th>"
       "<th>95 % CI</th><th>A/A0 normal</th><th>A/A0 at peak</th><th>pool depth [mm]</th><th>wet rms height [mm]</th>"
       "<th>n</th><th>failed</th><th>source (" << escape(file) << ")</th></tr>\n";
  for (const auto& r : sweep["table"]) {
    const std::string runs = run_groups(r["runs"]);
    o << "<tr><td>" << fmt(100 * num(r["target"]), "%.1f %%") << "</td><td>" << escape(r["water"].get<std::string>())
      << "</td><td>" << fmt(100 * num(r["coverage"]["mean"]), "%.1f %%") << "</td><td>" << fmt(num(r["mu_peak"]["mean"]))
      << "</td><td>" << fmt(100 * num(r["mu_ratio"]["mean"]), "%.1f %%") << "</td><td>&plusmn; "
      << fmt(100 * num(r["mu_ratio"]["ci95"]), "%.1f %%") << "</td><td>" << fmt(num(r["area_normal"]["mean"]))
      << "</td><td>" << fmt(num(r["area_at_peak"]["mean"])) << "</td><td>"
      << fmt(1e3 * num(r["mean_pool_depth"]["mean"])) << "</td><td>" << fmt(1e3 * num(r["wet_sq"]["mean"])) << "</td><td>"
      << r["mu_peak"]["n"].get<int>() << "</td><td>" << r["failed"].get<int>() << "</td><td class=\"src\">" << runs
      << "</td></tr>\n";
  }
  o << "</table>\n";
  std::string failed;
  for (const auto& r : sweep["runs"])
    if (r.value("status", "") != "ok")
      failed += "<li>run-" + std::to_string(r["index"].get<int>()) + ": " + escape(r.value("message", "")) + "</li>";
  if (!failed.empty()) o << "<p>Failed runs:</p><ul>" << failed << "</ul>\n";
  return o.str();
}

std::string roughness_table_html(const std::string& file, const nlohmann::json& sweep) {
  std::ostringstream o;
  o << "<table><tr><th>surfaces</th><th>&mu; peak</th><th>95 % CI</th><th>CoV</th><th>A/A0 at peak</th>"
       "<th>A/A0 normal</th><th>&kappa; (eq. 5.4)</th><th>h0 [mm]</th><th>n</th><th>failed</th><th>source ("
    << escape(file) << ")</th></tr>\n";
  for (const auto& r : sweep["table"]) {
    const std::string runs = run_groups(r["runs"]);
    o << "<tr><td>" << escape(r["label"].get<std::string>()) << "</td><td>" << fmt(num(r["mu_peak"]["mean"]))
      << "</td><td>&plusmn; " << fmt(num(r["mu_peak"]["ci95"])) << "</td><td>" << fmt(100 * num(r["mu_peak"]["cov"]), "%.1f %%")
      << "</td><td>" << fmt(num(r["area_at_peak"]["mean"])) << "</td><td>" << fmt(num(r["area_normal"]["mean"]))
      << "</td><td>" << fmt(num(r["kappa"]["mean"])) << "</td><td>" << fmt(1e3 * num(r["h0"]["mean"])) << "</td><td>"
      << r["mu_peak"]["n"].get<int>() << "</td><td>" << r["failed"].get<int>() << "</td><td class=\"src\">" << runs
      << "</td></tr>\n";
  }
  o << "</table>\n";
  if (!sweep["thesis"].empty()) {
    o << "<p>The thesis (Tables D.1&ndash;D.3 and C.1: 300 x 300, &delta;&Gamma; = &delta;&theta;/2, uz 9 mm, 10 "
         "realizations; its A' beside A/A0 at peak):</p><table><tr><th>surfaces</th><th>&mu;</th><th>CoV</th>"
         "<th>A'</th><th>CoV</th><th>&kappa;</th></tr>";
    for (const auto& t : sweep["thesis"])
      o << "<tr><td>" << escape(t.value("label", "")) << "</td><td>" << fmt(num(t["mu"])) << "</td><td>"
        << fmt(100 * num(t["mu_cov"]), "%.1f %%") << "</td><td>" << fmt(num(t["area"])) << "</td><td>"
        << fmt(100 * num(t["area_cov"]), "%.1f %%") << "</td><td>" << (t.contains("kappa") ? fmt(num(t["kappa"])) : "")
        << "</td></tr>";
    o << "</table>\n";
  }
  return o.str();
}

std::string scene_html(const std::string& file, const nlohmann::json& sweep) {
  const auto& sp = sweep["spec"];
  const auto& sc = sp["scene"];
  std::ostringstream o;
  o << "<table class=\"kv\">";
  auto row = [&](const std::string& k, const std::string& v) { o << "<tr><th>" << k << "</th><td>" << v << "</td></tr>"; };
  row("file", escape(file));
  const auto& s = sp["surface"];
  if (sp.contains("dataset"))
    row("surfaces", "dataset " + escape(sp["dataset"].get<std::string>()) + ": " + escape(sp["parameter"].get<std::string>()) +
                        " swept over " + std::to_string(sp["values"].size()) + " values; " + fmt(num(s["nx"]), "%.0f") +
                        " x " + fmt(num(s["ny"]), "%.0f") + ", dx " + fmt(num(s["dx"])) + " m, H " + fmt(num(s["hurst"])) +
                        ", h0 " + fmt(num(s["h0"])) + " m unless swept, q0/qL " + fmt(num(s["q0_ratio"])) +
                        ", seeds from " + fmt(num(s["seed"]), "%.0f"));
  else if (s.value("synthetic", false))
    row("surface", "synthetic self-affine: " + fmt(num(s["nx"]), "%.0f") + " x " + fmt(num(s["ny"]), "%.0f") +
                       ", dx " + fmt(num(s["dx"])) + " m, h0 " + fmt(num(s["h0"])) + " m, H " + fmt(num(s["hurst"])) +
                       ", q0/qL " + fmt(num(s["q0_ratio"])) + ", seeds from " + fmt(num(s["seed"]), "%.0f"));
  else
    row("surface", escape(s.value("path", "")));
  row("realizations", std::to_string(sp["realizations"].get<int>()));
  row("model", escape(sc["model"].get<std::string>()));
  if (sc["model"] == "hysteresis") {
    const auto& c = sc["compound"];
    row("scene", "hysteresis friction (Persson) at v " + fmt(num(sc["speeds"][0]), "%.3g") + " m/s, sigma0 " +
                     fmt(num(sc["pressure"])) + " Pa, T " + fmt(num(sc["temperature"]), "%.1f") + " C, flash temperature " +
                     (sc.value("flash_temperature", false) ? "on" : "off") + "; compound " +
                     escape(c.value("name", std::string("?"))) +
                     (c.value("synthetic", false) ? " <span class=\"flag\">(SYNTHETIC)</span>" : ""));
  } else {
    row("scene", "uz " + fmt(num(sc["uz"])) + " m in " + fmt(num(sc["normal_steps"]), "%.0f") + " steps, then ux " +
                     fmt(num(sc["ux"])) + " m in " + fmt(num(sc["shear_steps"]), "%.0f") + " steps; E " + fmt(num(sc["E"])) +
                     " Pa, &nu; " + fmt(num(sc["nu"])) + ", refine " + fmt(num(sc["refine"]), "%.0f") + ", tolerance " +
                     fmt(num(sc["tolerance"])) +
                     (sc.value("facet_normals", false) ? "; contact forces along the obstacle facets' normals"
                                                       : "; contact forces along the blended obstacle normals"));
  }
  if (sp.contains("tiling"))
    row("water", "drainage " + escape(sp["tiling"].get<std::string>()) + ", " + fmt(num(sp["connectivity"]), "%.0f") +
                     "-connected; drained fills up to the drained limit, standing water beyond");
  const auto& pv = sweep["provenance"];
  row("made by", escape("wetroad " + pv.value("version", std::string("?")) + ", " + pv.value("command", std::string("")) +
                        ", " + pv.value("created_utc", std::string(""))));
  row("wall time", fmt(num(pv["timings"]["total"]), "%.1f s") + " (this invocation), " +
                       fmt(num(pv["timings"]["ranks"]), "%.0f") + " rank(s)");
  o << "</table>\n";
  return o.str();
}

struct Point {
  double mpd_mm, sn;
  std::string source;
};

// The predicted skid numbers of one sweep, as labelled series: the hysteresis model's SN40R
// (100 mu at the sweep's speed, normally 17.9 m/s) and its IFI route (100 mu at 20 km/h carried
// to 64 km/h by exp(-(64 - 20)/Sp), Sp = 14.2 + 89.7 MPD); a contact model's 100 mu is the
// elastostatic friction, kept as its own series and never called a skid number.
struct PredictedSeries {
  std::string label;
  bool skid_number = false;
  std::vector<Point> points;
};

double ifi_route_sn(double mu_low, double mpd_mm) {
  const double sp = piarc_speed_constant(mpd_mm);
  return 100 * mu_low * std::exp(-(kSkidSpeed - 20) / sp);
}

// The runs that stand for the road in a skid test: every surface of a roughness sweep (dry); in
// a coverage sweep per realization the run at the largest drained coverage (the wet road a
// skid tester leaves behind; the dry run when there is none).
std::vector<const nlohmann::json*> skid_runs(const nlohmann::json& sweep) {
  std::vector<const nlohmann::json*> out;
  if (sweep.value("kind", "") == "roughness") {
    for (const auto& r : sweep["runs"])
      if (r.value("status", "") == "ok") out.push_back(&r);
    return out;
  }
  std::map<int, const nlohmann::json*> pick;
  for (const auto& r : sweep["runs"]) {
    if (r.value("status", "") != "ok" || r.value("water", "") == "stagnant") continue;
    const int z = r["realization"].get<int>();
    if (!pick.count(z) || num(r["target"]) > num((*pick[z])["target"])) pick[z] = &r;
  }
  for (const auto& [z, r] : pick) out.push_back(r);
  return out;
}

std::vector<PredictedSeries> predicted_series(const std::string& file, const nlohmann::json& sweep) {
  const bool roughness = sweep.value("kind", "") == "roughness";
  const auto& sc = sweep["spec"]["scene"];
  const bool hysteresis = sc.value("model", "") == "hysteresis";
  const std::string which = roughness ? ", dataset " + sweep["spec"].value("dataset", std::string("?")) : ", coverage sweep";
  std::vector<PredictedSeries> out;
  if (hysteresis) {
    const std::string flash = sc.value("flash_temperature", false) ? "flash temperature on" : "isothermal";
    const bool film = sc.contains("film") && sc["film"].is_object();
    const std::string film_label = film ? ", under a " + fmt(1e3 * num(sc["film"]["water_film"]), "%.3g") + " mm film (" +
                                              sc["film"].value("test", std::string("?")) + ")"
                                        : ", drained road (no film)";
    out.push_back({"hysteresis, 100 mu at " + fmt(num(sc["speeds"][0]), "%.3g") + " m/s" + film_label + " (" + flash + ")" + which, true, {}});
    out.push_back({"hysteresis, IFI route (comparison)" + which, true, {}});
  } else {
    out.push_back({"elastostatic 100 mu (" + sc.value("model", std::string("?")) + "), not a skid number" + which, false, {}});
  }
  for (const nlohmann::json* r : skid_runs(sweep)) {
    const double mpd = 1e3 * num(roughness ? (*r)["mpd"] : (*r)["ground_mpd"]);
    const std::string src = file + " " + run_group((*r)["index"].get<int>());
    out[0].points.push_back({mpd, 100 * num((*r)["contact"]["mu_peak"]), src});
    if (hysteresis) out[1].points.push_back({mpd, ifi_route_sn(num((*r)["contact"]["mu_low_speed"]), mpd), src});
  }
  return out;
}

std::string skid_section(const ReportInput& in, const std::string& chart_dir) {
  std::vector<PredictedSeries> all;
  for (const auto& [file, sweep] : in.sweeps)
    for (auto& p : predicted_series(file, sweep)) all.push_back(std::move(p));
  std::ostringstream o;
  o << "<h2>Skid number against mean profile depth</h2>\n"
       "<p>Predicted SN40R (ASTM E274, locked wheel at 64 km/h on the wetted road) from the hysteresis model: "
       "SN40R = 100 &mu; at 17.9 m/s (Persson's theory with the sealing of the pools, <code>--model hysteresis</code>; "
       "under the test's water film when the sweep ran with one, the default: the film's squeeze-out at speed), the "
       "prediction; and, as a labelled comparison, the IFI route: the model's &mu; at 20 km/h carried to 64 km/h with "
       "the speed constant Sp = 14.2 + 89.7 MPD (ASTM E1960; why the two differ: the section on wet friction at speed). Each point is the wet road a skid tester leaves: the surface at its "
       "drained limit with the pools sealed (local model; for a coverage sweep its largest drained coverage). The elastostatic &mu; of a contact-model sweep is the FEM's interlocking "
       "resistance of a frictionless block, a different mechanism: it is shown as its own series and is not a skid "
       "number. MPD of the dry surface per ISO 13473-1.</p>\n";
  PlotSpec spec{"SN40R against MPD", "MPD [mm]", "SN40R", false, false, {}};
  for (const auto& ps : all) {
    PlotSeries s{ps.label, {}, {}, "points", {}};
    for (const auto& p : ps.points) {
      s.x.push_back(p.mpd_mm);
      s.y.push_back(p.sn);
    }
    spec.series.push_back(s);
  }
  if (!in.measured.empty()) {
    PlotSeries ms{"measured (" + in.measured_path + ")", {}, {}, "points", {}};
    for (const auto& m : in.measured) {
      ms.x.push_back(m.mpd_mm);
      ms.y.push_back(m.sn40r);
    }
    spec.series.push_back(ms);
  }
  const std::string chart = chart_dir + "/skid.svg";
  write_svg_plot(chart, spec);
  o << figure(chart, "Predicted and measured skid numbers against MPD.");
  auto peak_line = [&](const std::string& what, const std::vector<double>& x, const std::vector<double>& y) {
    if (x.empty()) return std::string();
    const PeakEstimate p = peak_position(x, y);
    return "<li>" + escape(what) + ": peak at MPD " + fmt(p.mpd_mm, "%.3g mm") + " (" + fmt(p.value, "%.1f") + ", " +
           p.method + " over " + std::to_string(x.size()) + " points)</li>";
  };
  std::vector<double> mx, my;
  for (const auto& m : in.measured) {
    mx.push_back(m.mpd_mm);
    my.push_back(m.sn40r);
  }
  o << "<ul>" << peak_line("measured", mx, my);
  for (const auto& ps : all) {
    std::vector<double> x, y;
    for (const auto& p : ps.points) {
      x.push_back(p.mpd_mm);
      y.push_back(p.sn);
    }
    o << peak_line(ps.label, x, y);
  }
  o << "</ul>\n";
  o << "<table><tr><th>predicted point</th><th>series</th><th>MPD [mm]</th><th>SN40R (or 100 &mu;)</th></tr>";
  for (const auto& ps : all)
    for (const auto& p : ps.points)
      o << "<tr><td class=\"src\">" << escape(p.source) << "</td><td class=\"src\">" << escape(ps.label) << "</td><td>"
        << fmt(p.mpd_mm, "%.3f") << "</td><td>" << fmt(p.sn, "%.1f") << "</td></tr>";
  o << "</table>\n";
  if (!in.measured.empty()) {
    o << "<table><tr><th>site (" << escape(in.measured_path) << ")</th><th>MPD [mm]</th><th>SN40R</th><th>speed [km/h]</th>"
         "<th>Sp = 14.2 + 89.7 MPD [km/h]</th>"
      << (in.ifi ? "<th>F60</th>" : "") << "</tr>";
    for (const auto& m : in.measured) {
      const double sp = 14.2 + 89.7 * m.mpd_mm;
      const double s = m.speed_kmh.value_or(kSkidSpeed);
      o << "<tr><td>" << escape(m.site) << "</td><td>" << fmt(m.mpd_mm, "%.3f") << "</td><td>" << fmt(m.sn40r, "%.1f")
        << "</td><td>" << fmt(s, "%.0f") << "</td><td>" << fmt(sp, "%.1f") << "</td>";
      if (in.ifi)
        o << "<td>" << fmt(in.ifi->a + in.ifi->b * m.sn40r / 100 * std::exp((s - 60) / sp) + in.ifi->c * in.ifi->texture_tx, "%.3f")
          << "</td>";
      o << "</tr>";
    }
    o << "</table>\n";
    if (in.ifi)
      o << "<p>F60 = A + B FR(S) exp((S &minus; 60)/Sp) + C Tx with A = " << fmt(in.ifi->a) << ", B = " << fmt(in.ifi->b)
        << ", C = " << fmt(in.ifi->c) << ", Tx = " << fmt(in.ifi->texture_tx) << " mm (device constants given by the user).</p>\n";
  } else {
    o << "<p>No measured skid numbers given (<code>--measured site,mpd_mm,sn40r[,speed_kmh]</code>).</p>\n";
  }
  return o.str();
}

const char* kStyle =
    "body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}"
    "table{border-collapse:collapse;margin:1em 0;font-size:0.9em}td,th{border:1px solid #bbb;padding:3px 6px;"
    "text-align:right}th{background:#eee}table.kv td,table.kv th{text-align:left}td.src{font-family:monospace;"
    "font-size:0.8em;text-align:left}figure{margin:1em 0}figure svg{max-width:100%;height:auto}"
    ".flag{color:#a00;font-weight:bold}.ok{color:#060}";

}  // namespace

PeakEstimate peak_position(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::size_t best = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (y[k] > y[best]) best = k;
  PeakEstimate largest{x[best], y[best], "largest value"};
  if (n < 3) return largest;
  // Least squares y = c0 + c1 x + c2 x^2.
  Eigen::MatrixXd A(static_cast<Eigen::Index>(n), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) {
    A.row(Eigen::Index(k)) << 1.0, x[k], x[k] * x[k];
    b(Eigen::Index(k)) = y[k];
  }
  const std::optional<Eigen::VectorXd> fit = least_squares(A, b);
  if (!fit) return largest;
  const double c0 = (*fit)(0), c1 = (*fit)(1), c2 = (*fit)(2);
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  if (!(c2 < 0)) return largest;
  const double xv = -c1 / (2 * c2);
  if (xv < *lo || xv > *hi) return largest;
  return {xv, c0 + c1 * xv + c2 * xv * xv, "quadratic fit"};
}

void write_html_report(const std::string& path, const ReportInput& in) {
  if (in.sweeps.empty() && in.friction.empty())
    throw InputError("--sweep", "give at least one sweep (wetroad sweep-coverage or sweep-roughness --out) or friction "
                                "result (wetroad friction --out)");
  const std::string charts = temporary_sibling(path, ".charts");
  std::filesystem::create_directories(charts);
  std::ostringstream o;
  try {
    o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << escape(in.title)
      << "</title><style>" << kStyle << "</style></head><body>\n<h1>" << escape(in.title) << "</h1>\n"
      << "<p>Written by wetroad " << kVersion << " on " << utc_now_iso8601()
      << ". Charts are drawn by gnuplot and embedded; the file needs nothing else.</p>\n";
    o << summary_section_html(in);
    int k = 0;
    for (const auto& [file, summary] : in.friction)
      o << friction_section_html(file, summary, charts + "/friction" + std::to_string(k++));
    for (const auto& [file, sweep] : in.sweeps) {
      const std::string dir = charts + "/sweep" + std::to_string(k++);
      if (sweep.value("kind", "") == "roughness") {
        const auto files = write_roughness_plots(dir, sweep);
        o << "<h2>Friction against roughness: " << escape(file) << "</h2>\n"
          << scene_html(file, sweep) << validity_section(file, sweep)
          << figure(files[0], "Static friction against the swept parameter, with the thesis's Tables D.")
          << figure(files[1], "Contact area fraction at the friction peak, with the thesis's A'.")
          << roughness_table_html(file, sweep)
          << figure(files[2], "kappa of the quartic fit of each normal-load curve (eq. 5.4), with Table C.1.");
        continue;
      }
      const auto files = write_coverage_plots(dir, sweep);
      o << "<h2>Friction against water coverage: " << escape(file) << "</h2>\n"
        << scene_html(file, sweep) << validity_section(file, sweep)
        << figure(files[0], "Static friction on the wet surface relative to the dry surface (thesis Figure 5.25).")
        << figure(files[1], "Contact area fraction after the normal load and at the friction peak.")
        << coverage_table_html(file, sweep)
        << figure(files[2], "Mean depth of the water pools.")
        << figure(files[3], "Radial PSD of the wet surfaces: pools flatten the texture (thesis Figure 5.26).");
    }
    if (!in.sweeps.empty()) o << skid_section(in, charts) << skid_speed_section(in.sweeps, charts);
    o << "</body></html>\n";
  } catch (...) {
    std::filesystem::remove_all(charts);
    throw;
  }
  std::filesystem::remove_all(charts);
  write_text_atomically(path, o.str());
}

}  // namespace wr
