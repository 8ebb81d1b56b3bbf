#include "reports/sweep_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/hdf5_file.hpp"
#include "reports/plot.hpp"

namespace wr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double num(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : kNaN; }

// A table column: the statistic `stat` ("mean", "std", "ci95"; "" for a plain number) per row.
std::vector<double> column(const nlohmann::json& table, const std::string& name, const std::string& stat) {
  std::vector<double> v;
  for (const auto& row : table) v.push_back(stat.empty() ? num(row[name]) : num(row[name][stat]));
  return v;
}

std::vector<double> step_values(const nlohmann::json& steps, const char* key) {
  std::vector<double> v;
  for (const auto& s : steps) v.push_back(num(s[key]));
  return v;
}

}  // namespace

const SweepTableLayout& coverage_layout() {
  static const SweepTableLayout l{"wetroad coverage sweep", "target",
                                  {"coverage", "mu_peak", "mu_ratio", "mu_ratio_homogeneous", "area_at_peak", "area_normal",
                                   "mean_pool_depth", "wet_sq"}};
  return l;
}

const SweepTableLayout& roughness_layout() {
  static const SweepTableLayout l{"wetroad roughness sweep", "value",
                                  {"h0", "rms_slope", "mpd", "mu_peak", "area_at_peak", "area_normal", "kappa", "sn", "sp_kmh"}};
  return l;
}

void write_sweep_hdf5(const std::string& path, const nlohmann::json& sweep, const SweepTableLayout& layout) {
  Hdf5Writer w(path);
  w.write_text("/sweep", sweep.dump());
  w.write_attr("/", "kind", layout.kind);
  w.write_attr("/", "provenance", sweep["provenance"].dump());
  w.create_group("/table");
  const nlohmann::json& table = sweep["table"];
  w.write_vector("/table/" + layout.x, column(table, layout.x, ""));
  for (const auto& c : layout.stats) {
    w.write_vector("/table/" + c, column(table, c, "mean"));
    w.write_vector("/table/" + c + "_std", column(table, c, "std"));
    w.write_vector("/table/" + c + "_ci95", column(table, c, "ci95"));
  }
  w.create_group("/runs");
  for (const auto& r : sweep["runs"]) {
    char name[32];
    std::snprintf(name, sizeof name, "/runs/run-%04d", r["index"].get<int>());
    const std::string g = name;
    w.create_group(g);
    w.write_attr(g, "record", r.dump());
    if (r.contains("psd")) {
      w.write_vector(g + "/psd_q", r["psd"]["q"].get<std::vector<double>>());
      w.write_vector(g + "/psd_C", r["psd"]["C"].get<std::vector<double>>());
    }
    if (r.contains("contact") && r["contact"].contains("steps")) {  // contact models (hysteresis: none)
      const auto& steps = r["contact"]["steps"];
      for (const char* k : {"ux", "uz", "mu", "fz", "fx", "area_fraction"})
        w.write_vector(g + "/steps_" + k, step_values(steps, k));
    }
  }
  w.commit();
}

nlohmann::json read_sweep_hdf5(const std::string& path, const SweepTableLayout& layout) {
  Hdf5Reader r(path);
  const std::string kind = r.attr_string("/", "kind").value_or("");
  if (kind != layout.kind)
    throw InputError(path, "not a " + layout.kind.substr(8) + (kind.empty() ? "" : " (it is a " + kind.substr(8) + ")"));
  try {
    return nlohmann::json::parse(r.read_text("/sweep"));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("corrupt /sweep record: ") + e.what());
  }
}

nlohmann::json read_any_sweep_hdf5(const std::string& path) {
  const std::string kind = Hdf5Reader(path).attr_string("/", "kind").value_or("");
  for (const auto* layout : {&coverage_layout(), &roughness_layout()})
    if (kind == layout->kind) {
      nlohmann::json j = read_sweep_hdf5(path, *layout);
      j["kind"] = layout == &coverage_layout() ? "coverage" : "roughness";
      return j;
    }
  throw InputError(path, "not a sweep result (written by `wetroad sweep-coverage` or `sweep-roughness` --out)");
}

void write_sweep_csv(const std::string& path, const nlohmann::json& table, const SweepTableLayout& layout) {
  std::ostringstream o;
  o.precision(17);  // round-trip: a resumed or MPI sweep is compared to the digit
  o << layout.x << ",label,n,failed";
  for (const auto& c : layout.stats) o << "," << c << "," << c << "_std," << c << "_ci95";
  o << ",runs\n";
  for (const auto& row : table) {
    o << num(row[layout.x]) << "," << row.value("label", "") << "," << row["mu_peak"]["n"].get<int>() << ","
      << row["failed"].get<int>();
    for (const auto& c : layout.stats)
      for (const char* s : {"mean", "std", "ci95"}) {
        const double v = num(row[c][s]);
        o << ",";
        if (std::isfinite(v)) o << v;
      }
    o << ",";
    for (std::size_t k = 0; k < row["runs"].size(); ++k) o << (k ? " " : "") << row["runs"][k].get<int>();
    o << "\n";
  }
  write_text_atomically(path, o.str());
}

std::vector<std::string> write_coverage_plots(const std::string& dir, const nlohmann::json& sweep) {
  std::filesystem::create_directories(dir);
  const nlohmann::json& table = sweep["table"];
  std::vector<double> cov = column(table, "coverage", "mean");
  for (double& c : cov) c *= 100;
  auto percent = [](std::vector<double> v) {
    for (double& x : v) x *= 100;
    return v;
  };
  std::vector<std::string> files;
  const int n = sweep["spec"]["realizations"].get<int>();
  const std::string ci = n > 1 ? " (mean, 95 % CI over " + std::to_string(n) + " realizations)" : "";
  const std::string model = sweep["spec"]["scene"]["model"].get<std::string>();

  const bool hysteresis = model == "hysteresis";
  char title[160];
  if (hysteresis)
    std::snprintf(title, sizeof title, "Wet / dry hysteresis friction against water coverage (v = %.3g m/s)",
                  num(sweep["spec"]["scene"]["speeds"][0]));
  else
    std::snprintf(title, sizeof title, "Wet / dry static friction against water coverage (model %s)", model.c_str());
  PlotSpec mu{title, "water coverage [%]", "mu_wet / mu_dry [%]", false, false, {}};
  mu.series.push_back({(hysteresis ? "local sealing" : "mu_wet / mu_dry") + ci, cov,
                       percent(column(table, "mu_ratio", "mean")), "", percent(column(table, "mu_ratio", "ci95"))});
  if (hysteresis) {
    mu.series.push_back({"homogeneous sealing (PSD of the wet surface)" + ci, cov,
                         percent(column(table, "mu_ratio_homogeneous", "mean")), "",
                         percent(column(table, "mu_ratio_homogeneous", "ci95"))});
    // What the thesis's text says of its Figure 5.25 (sec. 5.4.2; elastostatic friction, FEM):
    // unchanged up to its drained limit of 40.45 %, one third of the dry value at 70 %.
    mu.series.push_back({"thesis Fig. 5.25 as its text states it (elastostatic)", {0, 40.45, 70}, {100, 100, 100.0 / 3},
                         "linespoints", {}});
  }
  // The drained limit (mean over the realizations): beyond it the water stands.
  double limit = 0;
  int nl = 0;
  for (const auto& r : sweep["runs"])
    if (r.contains("drained_limit")) {
      limit += num(r["drained_limit"]);
      ++nl;
    }
  if (nl > 0) {
    limit = 100 * limit / nl;
    double lo = 100, hi = 100;
    for (double v : mu.series[0].y)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    char label[64];
    std::snprintf(label, sizeof label, "drained limit %.1f %%", limit);
    mu.series.push_back({label, {limit, limit}, {lo, hi}, "lines", {}});
  }
  files.push_back(dir + "/mu_ratio.svg");
  write_svg_plot(files.back(), mu);

  PlotSpec area{"Contact area against water coverage (model " + model + ")", "water coverage [%]", "A/A0 [%]",
                false, false, {}};
  area.series.push_back({"after the normal load", cov, percent(column(table, "area_normal", "mean")), "",
                         percent(column(table, "area_normal", "ci95"))});
  area.series.push_back({"at the friction peak", cov, percent(column(table, "area_at_peak", "mean")), "",
                         percent(column(table, "area_at_peak", "ci95"))});
  files.push_back(dir + "/area.svg");
  write_svg_plot(files.back(), area);

  PlotSpec pool{"Mean depth of the pools against water coverage", "water coverage [%]", "mean pool depth [mm]", false,
                false, {}};
  std::vector<double> depth = column(table, "mean_pool_depth", "mean"), dci = column(table, "mean_pool_depth", "ci95");
  for (double& d : depth) d *= 1e3;
  for (double& d : dci) d *= 1e3;
  pool.series.push_back({"mean pool depth" + ci, cov, depth, "", dci});
  files.push_back(dir + "/pool_depth.svg");
  write_svg_plot(files.back(), pool);

  // Wet PSDs of the first realization (Figure 5.26). Values 12 decades below the largest are
  // round-off beyond the synthesized band (1e-45 and less), which would squash every curve into
  // the top of a log chart: they are left out.
  PlotSpec psd{"PSD of the wet surfaces (realization 0)", "q [1/m]", "C(q) [m^4]", true, true, {}};
  double c_max = 0;
  for (const auto& r : sweep["runs"])
    if (r["realization"].get<int>() == 0 && r.contains("psd"))
      for (const auto& c : r["psd"]["C"]) c_max = std::max(c_max, num(c));
  for (const auto& r : sweep["runs"]) {
    if (r["realization"].get<int>() != 0 || !r.contains("psd")) continue;
    PlotSeries s;
    char label[64];
    std::snprintf(label, sizeof label, "coverage %.0f %%", 100 * num(r["coverage"]));
    s.label = label;
    s.style = "lines";
    const auto q = r["psd"]["q"].get<std::vector<double>>();
    const auto c = r["psd"]["C"].get<std::vector<double>>();
    for (std::size_t k = 0; k < q.size(); ++k)
      if (q[k] > 0 && c[k] > 1e-12 * c_max) {
        s.x.push_back(q[k]);
        s.y.push_back(c[k]);
      }
    psd.series.push_back(std::move(s));
  }
  files.push_back(dir + "/wet_psd.svg");
  write_svg_plot(files.back(), psd);
  return files;
}

std::vector<std::string> write_roughness_plots(const std::string& dir, const nlohmann::json& sweep) {
  std::filesystem::create_directories(dir);
  const nlohmann::json& table = sweep["table"];
  const std::string parameter = sweep["spec"]["parameter"].get<std::string>();
  const bool h0 = parameter == "h0";
  const double scale = h0 ? 1e3 : 1.0;  // h0 in mm
  const std::string xlabel = h0 ? "h0 [mm]" : parameter == "hurst" ? "Hurst exponent H" : "q1 / q1hat";
  const bool logx = parameter != "hurst";
  std::vector<double> x = column(table, "value", "");
  for (double& v : x) v *= scale;
  std::vector<double> tx;
  for (const auto& t : sweep["thesis"]) tx.push_back(scale * num(t["value"]));
  auto thesis = [&](const char* key) {
    std::vector<double> xs, ys;
    for (const auto& t : sweep["thesis"])
      if (t.contains(key)) {
        xs.push_back(scale * num(t["value"]));
        ys.push_back(num(t[key]));
      }
    return PlotSeries{"thesis (300 x 300, dGamma = dtheta/2)", xs, ys, "points", {}};
  };
  const std::string model = sweep["spec"]["scene"]["model"].get<std::string>();
  const std::string n = std::to_string(sweep["spec"]["realizations"].get<int>());
  std::vector<std::string> files;
  auto chart = [&](const char* file, const std::string& title, const std::string& ylabel, const char* column_name,
                   const char* thesis_key) {
    PlotSpec p{title, xlabel, ylabel, logx, false, {}};
    p.series.push_back({"wetroad " + model + ", mean and 95 % CI of " + n, x, column(table, column_name, "mean"),
                        "", column(table, column_name, "ci95")});
    p.series.push_back(thesis(thesis_key));
    files.push_back(dir + "/" + file);
    write_svg_plot(files.back(), p);
  };
  chart("mu.svg", "Static friction against " + parameter, "mu (peak of the shear test)", "mu_peak", "mu");
  chart("area.svg", "Contact area against " + parameter, "A/A0 (at the friction peak)", "area_at_peak", "area");
  chart("kappa.svg", "Low-pressure slope kappa (quartic fit, eq. 5.4) against " + parameter, "kappa", "kappa", "kappa");
  return files;
}

}  // namespace wr
