#include "reports/skid_speed_section.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "reports/html_parts.hpp"
#include "reports/plot.hpp"

namespace wr {
namespace {

using html::escape;
using html::fmt;

double num(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : NAN; }

struct SurfacePoint {
  std::string sweep, label;
  double mpd_mm = NAN, sn = NAN, sn20 = NAN, sp = NAN;  // sp: NaN when friction does not fall
  std::vector<std::pair<double, double>> sn_speed;       // km/h, SN
};

// The runs a skid tester would meet (as the skid-number chart picks them): every ok run of a
// roughness sweep; the dry runs of a coverage sweep (the film model brings its own water).
std::vector<SurfacePoint> film_points(const std::string& file, const nlohmann::json& sweep) {
  std::vector<SurfacePoint> out;
  const bool roughness = sweep.value("kind", "") == "roughness";
  for (const auto& r : sweep["runs"]) {
    if (r.value("status", "") != "ok" || !r.contains("contact") || !r["contact"].contains("sn_against_speed")) continue;
    if (!roughness && num(r["target"]) != 0) continue;
    SurfacePoint p;
    p.sweep = file;
    p.label = roughness ? r.value("label", std::string("?")) : "coverage sweep surface";
    p.mpd_mm = 1e3 * num(roughness ? r["mpd"] : r["ground_mpd"]);
    const auto& c = r["contact"];
    p.sn = num(c["sn"]);
    p.sp = num(c["sp_kmh"]);
    for (const auto& sv : c["sn_against_speed"]) p.sn_speed.push_back({num(sv[0]), num(sv[1])});
    if (!p.sn_speed.empty()) p.sn20 = p.sn_speed.front().second;
    out.push_back(p);
  }
  return out;
}

std::string sp_chart(const std::vector<SurfacePoint>& pts, const std::string& chart_dir) {
  PlotSpec spec{"speed constant Sp against MPD", "MPD [mm]", "Sp [km/h]", false, true, {}};
  PlotSeries model{"predicted (hysteresis + water film)", {}, {}, "points", {}};
  double lo = 1e9, hi = 0;
  for (const auto& p : pts)
    if (std::isfinite(p.sp) && std::isfinite(p.mpd_mm)) {
      model.x.push_back(p.mpd_mm);
      model.y.push_back(p.sp);
      lo = std::min(lo, p.mpd_mm);
      hi = std::max(hi, p.mpd_mm);
    }
  PlotSeries piarc{"ASTM E1960: Sp = 14.2 + 89.7 MPD", {}, {}, "lines", {}};
  if (hi <= lo) lo = 0.1, hi = 1.2;
  for (int i = 0; i <= 20; ++i) {
    const double m = lo + (hi - lo) * i / 20;
    piarc.x.push_back(m);
    piarc.y.push_back(piarc_speed_constant(m));
  }
  spec.series = {model, piarc};
  const std::string chart = chart_dir + "/sp_mpd.svg";
  write_svg_plot(chart, spec);
  return html::figure(chart, "Predicted speed constant against MPD, beside PIARC's regression (ASTM E1960).");
}

// SN against speed, one curve per surface label (mean over its realizations), at most 12.
std::string speed_chart(const std::vector<SurfacePoint>& pts, const std::string& chart_dir) {
  std::map<std::string, std::vector<const SurfacePoint*>> by_label;
  for (const auto& p : pts) by_label[p.sweep + ": " + p.label].push_back(&p);
  PlotSpec spec{"skid number against speed under the film", "speed [km/h]", "SN", false, false, {}};
  for (const auto& [label, group] : by_label) {
    if (spec.series.size() >= 12) break;
    PlotSeries s{label + " (MPD " + fmt(group.front()->mpd_mm, "%.2f") + " mm)", {}, {}, "linespoints", {}};
    const std::size_t n = group.front()->sn_speed.size();
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (const SurfacePoint* p : group) sum += p->sn_speed.size() == n ? p->sn_speed[i].second : NAN;
      s.x.push_back(group.front()->sn_speed[i].first);
      s.y.push_back(sum / group.size());
    }
    spec.series.push_back(s);
  }
  const std::string chart = chart_dir + "/sn_speed_surfaces.svg";
  write_svg_plot(chart, spec);
  return html::figure(chart, "Predicted skid number against speed per surface (mean over realizations).");
}

}  // namespace

std::string skid_speed_section(const std::vector<std::pair<std::string, nlohmann::json>>& sweeps, const std::string& chart_dir) {
  std::vector<SurfacePoint> pts;
  for (const auto& [file, sweep] : sweeps)
    for (auto& p : film_points(file, sweep)) pts.push_back(std::move(p));
  if (pts.empty()) return "";
  std::ostringstream o;
  o << "<h2>Wet friction at speed: skid numbers and the speed constant</h2>\n"
       "<p>Each surface under the test's water film (ASTM E274: 0.5 mm, locked wheel): the film drains through the "
       "texture while a road element is under the tread (docs/friction-model.md, \"Wet friction at speed\"), and the "
       "speed constant Sp is ASTM E1960's exponential fitted to the predicted SN over 20&ndash;100 km/h. PIARC's "
       "regression Sp = 14.2 + 89.7 MPD is a measured comparison, not an input.</p>\n";
  o << sp_chart(pts, chart_dir) << speed_chart(pts, chart_dir);
  // The two routes to SN40R side by side, with their ratio.
  double lo = INFINITY, hi = 0;
  o << "<table><tr><th>surface</th><th>MPD [mm]</th><th>SN40R, this model</th><th>SN at 20 km/h</th>"
       "<th>IFI route: SN20 exp(&minus;44/Sp<sub>E1960</sub>)</th><th>ratio</th><th>Sp, model [km/h]</th>"
       "<th>Sp, E1960 [km/h]</th></tr>";
  for (const auto& p : pts) {
    const double sp_e = piarc_speed_constant(p.mpd_mm), ifi = p.sn20 * std::exp(-(64.0 - 20.0) / sp_e);
    const double ratio = p.sn / ifi;
    if (std::isfinite(ratio)) lo = std::min(lo, ratio), hi = std::max(hi, ratio);
    o << "<tr><td class=\"src\">" << escape(p.sweep + ": " + p.label) << "</td><td>" << fmt(p.mpd_mm, "%.3f") << "</td><td>"
      << fmt(p.sn, "%.1f") << "</td><td>" << fmt(p.sn20, "%.1f") << "</td><td>" << fmt(ifi, "%.1f") << "</td><td>"
      << fmt(ratio, "%.2f") << "</td><td>" << (std::isfinite(p.sp) ? fmt(p.sp, "%.0f") : std::string("none")) << "</td><td>"
      << fmt(sp_e, "%.0f") << "</td></tr>";
  }
  o << "</table>\n";
  o << "<p><b>Why the two routes differ</b> (the model's SN40R is " << fmt(lo, "%.2f") << " to " << fmt(hi, "%.2f")
    << " times the IFI route's here): the IFI route carries the model's friction at 20 km/h to 64 km/h with PIARC's measured Sp, which holds "
       "every mechanism of real skid tests; this model's own Sp holds only the film's squeeze-out and the rubber's "
       "hysteresis (with the flash temperature when on). On these surfaces the 0.5 mm film fits into the texture's voids "
       "or drains within a fraction of a millisecond under a rib of the E501 tyre, so the model's friction hardly falls "
       "with speed. What the regression holds beyond it (measured in docs/validation.md, \"Wet friction at speed\"): the "
       "thin films on the microtexture that a self-affine extension of the measured band does not have, the water's "
       "inertia ahead of the tyre (&rho;v&sup2;/2 = 0.16 MPa at 64 km/h, half the tread pressure), and a real compound's "
       "fall of wet friction with speed. The model's SN40R is the prediction; the IFI route is a labelled "
       "comparison.</p>\n";
  return o.str();
}

}  // namespace wr
