#include "reports/summary_section.hpp"

#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "reports/html_parts.hpp"

namespace wr {
namespace {

using html::escape;
using html::fmt;

double num(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : NAN; }

struct Row {
  std::string surface, source;
  double mpd_mm = NAN, sn = NAN, band_lo = NAN, band_hi = NAN, sp = NAN, fr60 = NAN;
  std::string band_kind;  // "inputs 5-95 %" or "realizations 95 % CI"
  std::set<std::string> failed;
  int n = 0;
};

std::string cell(double v, const char* f) { return std::isfinite(v) ? fmt(v, f) : std::string("&ndash;"); }

void failed_checks(const nlohmann::json& validity, std::set<std::string>& out) {
  if (!validity.is_object() || !validity.contains("checks")) return;
  for (const auto& c : validity["checks"])
    if (!c.value("passed", true)) out.insert(c.value("check", std::string("?")));
}

Row friction_row(const std::string& file, const nlohmann::json& j) {
  Row r;
  r.surface = file;
  r.source = "friction";
  r.mpd_mm = 1e3 * num(j.value("mpd", nlohmann::json()));
  if (j.contains("water_film")) {
    const auto& f = j["water_film"];
    r.sn = num(f["sn"]);
    r.sp = num(f["sp_kmh"]);
    r.fr60 = num(f["fr60"]);
    if (f.contains("band")) r.band_lo = num(f["band"]["p05"]), r.band_hi = num(f["band"]["p95"]), r.band_kind = "inputs, 5-95 %";
  }
  failed_checks(j["validity"], r.failed);
  r.n = 1;
  return r;
}

// Hysteresis sweeps: per surface (a roughness sweep's label; a coverage sweep's dry surface),
// the mean over realizations and its 95 % interval (t distribution, as the sweep tables).
std::vector<Row> sweep_rows(const std::string& file, const nlohmann::json& sweep) {
  std::map<std::string, std::vector<const nlohmann::json*>> groups;
  const bool roughness = sweep.value("kind", "") == "roughness";
  for (const auto& r : sweep["runs"]) {
    if (r.value("status", "") != "ok" || !r.contains("contact") || !r["contact"].contains("sn_against_speed")) continue;
    if (!roughness && num(r["target"]) != 0) continue;
    groups[roughness ? r.value("label", std::string("?")) : "surface of the coverage sweep"].push_back(&r);
  }
  std::vector<Row> out;
  for (const auto& [label, runs] : groups) {
    Row row;
    row.surface = label;
    row.source = file;
    row.n = static_cast<int>(runs.size());
    double m = 0, sn = 0, sn2 = 0, sp = 0, fr = 0, b05 = 0, b95 = 0;
    int nsp = 0, nband = 0;
    for (const nlohmann::json* r : runs) {
      const auto& c = (*r)["contact"];
      m += 1e3 * num(roughness ? (*r)["mpd"] : (*r)["ground_mpd"]);
      sn += num(c["sn"]), sn2 += num(c["sn"]) * num(c["sn"]);
      fr += num(c["fr60"]);
      if (c["sp_kmh"].is_number()) sp += num(c["sp_kmh"]), ++nsp;
      failed_checks(c["validity"], row.failed);
      if (c.contains("sn_band")) b05 += num(c["sn_band"]["p05"]), b95 += num(c["sn_band"]["p95"]), ++nband;
    }
    const double n = runs.size();
    row.mpd_mm = m / n;
    row.sn = sn / n;
    row.fr60 = fr / n;
    row.sp = nsp ? sp / nsp : NAN;
    if (n > 1) {
      const double sd = std::sqrt(std::max(0.0, (sn2 - n * row.sn * row.sn) / (n - 1)));
      const double t = n >= 30 ? 1.96 : (n >= 10 ? 2.26 : (n >= 5 ? 2.78 : 4.30));  // Student t, 95 %
      row.band_lo = row.sn - t * sd / std::sqrt(n);
      row.band_hi = row.sn + t * sd / std::sqrt(n);
      row.band_kind = "realizations, 95 % CI";
    }
    if (nband > 0) {  // the inputs' band (mean of the runs' 5-95 %), beside the realizations' interval
      row.band_kind = (n > 1 ? "realizations 95 % CI " + fmt(row.band_lo, "%.1f") + " &ndash; " + fmt(row.band_hi, "%.1f") + "; " : std::string()) +
                      "inputs 5-95 %";
      row.band_lo = b05 / nband;
      row.band_hi = b95 / nband;
    }
    out.push_back(row);
  }
  return out;
}

}  // namespace

std::string summary_section_html(const ReportInput& in) {
  std::vector<Row> rows;
  for (const auto& [file, j] : in.friction) rows.push_back(friction_row(file, j));
  std::vector<std::string> not_skid;
  for (const auto& [file, sweep] : in.sweeps) {
    const bool hysteresis = sweep["spec"]["scene"].value("model", "") == "hysteresis";
    if (!hysteresis) {
      not_skid.push_back(file);
      continue;
    }
    for (Row& r : sweep_rows(file, sweep)) rows.push_back(std::move(r));
  }
  std::ostringstream o;
  o << "<h2>Summary</h2>\n<table><tr><th>surface</th><th>source</th><th>MPD [mm]</th><th>SN40R predicted</th>"
       "<th>band</th><th>Sp [km/h]</th><th>FR60</th>"
    << (in.ifi ? "<th>F60</th>" : "") << "<th>checks that failed</th></tr>";
  for (const Row& r : rows) {
    std::string failed;
    for (const std::string& f : r.failed) failed += (failed.empty() ? "" : "; ") + f;
    o << "<tr><td class=\"src\">" << escape(r.surface) << "</td><td class=\"src\">" << escape(r.source)
      << (r.n > 1 ? " (" + std::to_string(r.n) + " realizations)" : "") << "</td><td>" << cell(r.mpd_mm, "%.3f")
      << "</td><td><b>" << (std::isfinite(r.sn) ? fmt(r.sn, "%.1f") : std::string("no film: no skid number")) << "</b></td><td>"
      << (std::isfinite(r.band_lo) ? fmt(r.band_lo, "%.1f") + " &ndash; " + fmt(r.band_hi, "%.1f") + " (" + r.band_kind + ")"
                                   : std::string("&ndash;"))
      << "</td><td>" << (std::isfinite(r.sp) ? fmt(r.sp, "%.0f") : std::string(std::isfinite(r.sn) ? "none (no fall)" : "&ndash;"))
      << "</td><td>" << cell(r.fr60, "%.3f") << "</td>";
    if (in.ifi) o << "<td>" << cell(in.ifi->a + in.ifi->b * r.fr60 + in.ifi->c * in.ifi->texture_tx, "%.3f") << "</td>";
    o << "<td class=\"" << (failed.empty() ? "ok" : "flag") << "\">" << (failed.empty() ? "none" : escape(failed)) << "</td></tr>";
  }
  for (const MeasuredSkid& m : in.measured)
    o << "<tr><td class=\"src\">" << escape(m.site) << "</td><td class=\"src\">measured (" << escape(in.measured_path)
      << ")</td><td>" << fmt(m.mpd_mm, "%.3f") << "</td><td>" << fmt(m.sn40r, "%.1f") << " measured"
      << (m.speed_kmh ? " at " + fmt(*m.speed_kmh, "%.0f") + " km/h" : std::string()) << "</td><td>&ndash;</td><td>"
      << fmt(14.2 + 89.7 * m.mpd_mm, "%.0f") << " (E1960)</td><td>&ndash;</td>" << (in.ifi ? "<td>&ndash;</td>" : "")
      << "<td>&ndash;</td></tr>";
  o << "</table>\n<p>SN40R: ASTM E274's locked wheel at 64 km/h under its 0.5 mm film, predicted by the hysteresis model "
       "with the film's squeeze-out (a dry road has no skid number). The band is the spread over the inputs' ranges "
       "(<code>friction --band</code>) or over the sweep's realizations. FR60 is the model's friction at 60 km/h"
    << (in.ifi ? ", F60 = A + B FR60 + C Tx with the device constants given" : "")
    << ". Details of every row below.";
  if (!not_skid.empty()) {
    o << " Not in this table (elastostatic friction of the FEM or spectral model, not a skid number):";
    for (const std::string& f : not_skid) o << " " << escape(f);
    o << ".";
  }
  o << "</p>\n";
  return o.str();
}

}  // namespace wr
