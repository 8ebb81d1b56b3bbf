#include "reports/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/io/atomic_output.hpp"
#include "reports/sweep_outputs.hpp"
#include "reports/plot.hpp"
#include "wetroad/version.hpp"

namespace wr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSkidSpeed = 64.0;  // km/h: SN40R is measured at 40 mph

double num(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : kNaN; }

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

std::string fmt(double v, const char* f = "%.4g") {
  if (!std::isfinite(v)) return "&ndash;";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  for (auto& s : out) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    s = b == std::string::npos ? "" : s.substr(b, e - b + 1);
  }
  return out;
}

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

std::string figure(const std::string& svg_file, const std::string& caption) {
  return "<figure>" + inline_svg(svg_file) + "<figcaption>" + caption + "</figcaption></figure>\n";
}

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
  row("scene", "uz " + fmt(num(sc["uz"])) + " m in " + fmt(num(sc["normal_steps"]), "%.0f") + " steps, then ux " +
                   fmt(num(sc["ux"])) + " m in " + fmt(num(sc["shear_steps"]), "%.0f") + " steps; E " + fmt(num(sc["E"])) +
                   " Pa, &nu; " + fmt(num(sc["nu"])) + ", refine " + fmt(num(sc["refine"]), "%.0f") + ", tolerance " +
                   fmt(num(sc["tolerance"])) +
                   (sc.value("facet_normals", false) ? "; contact forces along the obstacle facets' normals"
                                                     : "; contact forces along the blended obstacle normals"));
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

// Predicted SN40R = 100 mu of the drained (skid-test) road: per realization, the run at the
// largest drained coverage (the dry run when there is none).
std::vector<Point> predicted_points(const std::string& file, const nlohmann::json& sweep) {
  std::vector<Point> pts;
  if (sweep.value("kind", "") == "roughness") {  // every surface of the sweep, dry
    for (const auto& r : sweep["runs"])
      if (r.value("status", "") == "ok")
        pts.push_back({1e3 * num(r["mpd"]), 100 * num(r["contact"]["mu_peak"]), file + " " + run_group(r["index"].get<int>())});
    return pts;
  }
  std::map<int, const nlohmann::json*> pick;
  for (const auto& r : sweep["runs"]) {
    if (r.value("status", "") != "ok" || r.value("water", "") == "stagnant") continue;
    const int z = r["realization"].get<int>();
    if (!pick.count(z) || num(r["target"]) > num((*pick[z])["target"])) pick[z] = &r;
  }
  for (const auto& [z, r] : pick)
    pts.push_back({1e3 * num((*r)["ground_mpd"]), 100 * num((*r)["contact"]["mu_peak"]),
                   file + " " + run_group((*r)["index"].get<int>())});
  return pts;
}

std::string skid_section(const ReportInput& in, const std::string& chart_dir) {
  std::vector<Point> pred;
  for (const auto& [file, sweep] : in.sweeps)
    for (const auto& p : predicted_points(file, sweep)) pred.push_back(p);
  std::ostringstream o;
  o << "<h2>Skid number against mean profile depth</h2>\n"
       "<p>Predicted SN40R = 100 &mu;, &mu; the static (elastostatic) friction of the shear test: for coverage "
       "sweeps on the drained wet road (largest drained coverage of each realization), for roughness sweeps on each "
       "surface; MPD of the dry surface per ISO 13473-1.</p>\n";
  PlotSpec spec{"SN40R against MPD", "MPD [mm]", "SN40R", false, false, {}};
  PlotSeries ps{"predicted (100 mu)", {}, {}, "points", {}};
  for (const auto& p : pred) {
    ps.x.push_back(p.mpd_mm);
    ps.y.push_back(p.sn);
  }
  spec.series.push_back(ps);
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
  auto peak_line = [&](const char* what, const std::vector<double>& x, const std::vector<double>& y) {
    if (x.empty()) return std::string();
    const PeakEstimate p = peak_position(x, y);
    return std::string("<li>") + what + ": peak at MPD " + fmt(p.mpd_mm, "%.3g mm") + " (SN40R " + fmt(p.value, "%.1f") +
           ", " + p.method + " over " + std::to_string(x.size()) + " points)</li>";
  };
  std::vector<double> mx, my;
  for (const auto& m : in.measured) {
    mx.push_back(m.mpd_mm);
    my.push_back(m.sn40r);
  }
  o << "<ul>" << peak_line("measured", mx, my) << peak_line("predicted", ps.x, ps.y) << "</ul>\n";
  o << "<table><tr><th>predicted point</th><th>MPD [mm]</th><th>SN40R</th></tr>";
  for (const auto& p : pred)
    o << "<tr><td class=\"src\">" << escape(p.source) << "</td><td>" << fmt(p.mpd_mm, "%.3f") << "</td><td>"
      << fmt(p.sn, "%.1f") << "</td></tr>";
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

std::vector<MeasuredSkid> read_measured_skid_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the measured skid-number CSV");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path, "empty file (expected the header site,mpd_mm,sn40r[,speed_kmh])");
  const auto head = split_csv_line(line);
  if (head.size() < 3 || head[0] != "site" || head[1] != "mpd_mm" || head[2] != "sn40r" ||
      (head.size() > 3 && head[3] != "speed_kmh") || head.size() > 4)
    throw InputError(path, "line 1: the header must be site,mpd_mm,sn40r[,speed_kmh]");
  std::vector<MeasuredSkid> out;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto f = split_csv_line(line);
    if (f.size() != head.size())
      throw InputError(path, "line " + std::to_string(n) + ": " + std::to_string(head.size()) + " fields expected");
    auto value = [&](const std::string& s, const char* what, double lo, double hi) {
      std::size_t used = 0;
      double v = kNaN;
      try {
        v = std::stod(s, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != s.size() || !(v >= lo && v <= hi))
        throw InputError(path, "line " + std::to_string(n) + ": " + what + " '" + s + "' is not a number in [" +
                                   fmt(lo, "%g") + ", " + fmt(hi, "%g") + "]");
      return v;
    };
    MeasuredSkid m;
    m.site = f[0];
    m.mpd_mm = value(f[1], "mpd_mm", 0, 10);
    m.sn40r = value(f[2], "sn40r", 0, 150);
    if (f.size() > 3 && !f[3].empty()) m.speed_kmh = value(f[3], "speed_kmh", 1, 300);
    out.push_back(m);
  }
  if (out.empty()) throw InputError(path, "no data rows");
  return out;
}

PeakEstimate peak_position(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::size_t best = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (y[k] > y[best]) best = k;
  PeakEstimate largest{x[best], y[best], "largest value"};
  if (n < 3) return largest;
  // Least squares y = c0 + c1 x + c2 x^2 through the normal equations (3 x 3, Cramer's rule).
  double s[5] = {0, 0, 0, 0, 0}, t[3] = {0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) {
    double p = 1;
    for (int i = 0; i < 5; ++i, p *= x[k]) s[i] += p;
    t[0] += y[k];
    t[1] += y[k] * x[k];
    t[2] += y[k] * x[k] * x[k];
  }
  auto det3 = [](double a, double b, double c, double d, double e, double f, double g, double h, double i) {
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  };
  const double d = det3(s[0], s[1], s[2], s[1], s[2], s[3], s[2], s[3], s[4]);
  if (std::abs(d) < 1e-300) return largest;
  const double c1 = det3(s[0], t[0], s[2], s[1], t[1], s[3], s[2], t[2], s[4]) / d;
  const double c2 = det3(s[0], s[1], t[0], s[1], s[2], t[1], s[2], s[3], t[2]) / d;
  const double c0 = det3(t[0], s[1], s[2], t[1], s[2], s[3], t[2], s[3], s[4]) / d;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  if (!(c2 < 0)) return largest;
  const double xv = -c1 / (2 * c2);
  if (xv < *lo || xv > *hi) return largest;
  return {xv, c0 + c1 * xv + c2 * xv * xv, "quadratic fit"};
}

void write_html_report(const std::string& path, const ReportInput& in) {
  if (in.sweeps.empty()) throw InputError("--sweep", "give at least one sweep (wetroad sweep-coverage or sweep-roughness --out)");
  const std::string charts = temporary_sibling(path) + ".charts";
  std::filesystem::create_directories(charts);
  std::ostringstream o;
  try {
    o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << escape(in.title)
      << "</title><style>" << kStyle << "</style></head><body>\n<h1>" << escape(in.title) << "</h1>\n"
      << "<p>Written by wetroad " << kVersion << " on " << utc_now_iso8601()
      << ". Charts are drawn by gnuplot and embedded; the file needs nothing else.</p>\n";
    int k = 0;
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
        << figure(files[3], "Mean depth of the water pools.")
        << figure(files[2], "Radial PSD of the wet surfaces: pools flatten the texture (thesis Figure 5.26).");
    }
    o << skid_section(in, charts);
    o << "</body></html>\n";
  } catch (...) {
    std::filesystem::remove_all(charts);
    throw;
  }
  std::filesystem::remove_all(charts);
  write_text_atomically(path, o.str());
}

}  // namespace wr
