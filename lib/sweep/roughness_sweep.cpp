#include "lib/core/provenance.hpp"
#include "lib/sweep/roughness_sweep.hpp"
#include "lib/sweep/sweep_engine.hpp"
#include "lib/core/number_text.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "lib/contact/area_load_fits.hpp"
#include "lib/core/errors.hpp"
#include "lib/sweep/hysteresis_run.hpp"
#include "lib/sweep/sample_statistics.hpp"
#include "roads/height_stats.hpp"
#include "roads/mpd.hpp"
#include "water/rain_fill.hpp"

namespace wr {
namespace {

// The thesis's surfaces (Table 5.1): 300 x 300 over 3 cm, q0 = 5 qL, H = 0.7, h0 = 0.71 mm.
SynthParams thesis_surface() {
  SynthParams p;
  p.nx = p.ny = 300;
  p.dx = 1e-4;
  p.hurst = 0.7;
  p.q0_ratio = 5;
  p.h0 = 7.1e-4;
  p.seed = 1;
  p.sampling = Sampling::thesis;  // Table 5.1's q1hat = 2 pi / dx on the dx lattice (sec. 4.1.1)
  return p;
}

std::string label_of(RoughnessParameter p, double v) {
  char b[64];
  if (p == RoughnessParameter::h0) std::snprintf(b, sizeof b, "h0 = %.3g mm", 1e3 * v);
  else if (p == RoughnessParameter::hurst) std::snprintf(b, sizeof b, "H = %.2g", v);
  else std::snprintf(b, sizeof b, "q1/q1hat = %.4g", v);
  return b;
}

}  // namespace

const char* parameter_name(RoughnessParameter p) {
  switch (p) {
    case RoughnessParameter::h0: return "h0";
    case RoughnessParameter::hurst: return "hurst";
    case RoughnessParameter::q1_fraction: return "q1_fraction";
  }
  return "?";
}

RoughnessSweepSpec roughness_dataset(const std::string& name) {
  RoughnessSweepSpec s;
  s.dataset = name;
  s.base = thesis_surface();
  if (name == "A") {
    s.parameter = RoughnessParameter::h0;
    for (double e : {-4.14, -4.02, -3.89, -3.77, -3.64, -3.52, -3.39, -3.27, -3.14}) s.values.push_back(std::pow(10.0, e));
  } else if (name == "B") {
    s.parameter = RoughnessParameter::hurst;
    s.values = {0.5, 0.6, 0.7, 0.8, 0.9};
  } else if (name == "C") {
    s.parameter = RoughnessParameter::q1_fraction;
    s.values = {0.125, 0.25, 0.5, 1.0};
  } else {
    throw InputError("--dataset", "must be A, B or C (the thesis's datasets, Table 5.1)");
  }
  return s;
}

void check_roughness_spec(const RoughnessSweepSpec& s) {
  if (s.values.empty()) throw InputError("--values", "give at least one value");
  for (double v : s.values) {
    const bool ok = s.parameter == RoughnessParameter::h0       ? v > 0
                    : s.parameter == RoughnessParameter::hurst ? (v > 0 && v < 1)
                                                               : (v > 0 && v <= 1);
    if (!ok) throw InputError("--values", std::string("a value out of range for ") + parameter_name(s.parameter));
  }
  std::vector<double> sorted = s.values;
  std::sort(sorted.begin(), sorted.end());
  if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
    throw InputError("--values", "the value " + number_text(*twice) + " is given twice; give each value once");
  check_realizations(s.realizations, s.base.seed);
  if (s.hysteresis) check_friction_scene(*s.hysteresis);
  else check_contact_scene(s.scene);
  // Every surface the sweep will synthesize, checked now rather than when its run starts.
  for (double v : s.values) {
    SynthParams p = s.base;
    if (s.parameter == RoughnessParameter::h0) p.h0 = v;
    if (s.parameter == RoughnessParameter::hurst) p.hurst = v;
    if (s.parameter == RoughnessParameter::q1_fraction) p.q1_fraction = v;
    validate(p);
  }
}

int roughness_run_count(const RoughnessSweepSpec& s) { return int(s.values.size()) * s.realizations; }

nlohmann::json roughness_spec_json(const RoughnessSweepSpec& s) {
  const SynthParams& p = s.base;
  return {{"dataset", s.dataset},
          {"parameter", parameter_name(s.parameter)},
          {"values", s.values},
          {"realizations", s.realizations},
          {"surface",
           {{"nx", p.nx}, {"ny", p.ny}, {"dx", p.dx}, {"h0", p.h0}, {"hurst", p.hurst}, {"q0_ratio", p.q0_ratio},
            {"q1", p.q1 ? nlohmann::json(*p.q1) : nlohmann::json(nullptr)}, {"q1_fraction", p.q1_fraction},
            {"oversample", p.oversample}, {"sampling", sampling_name(p.sampling)}, {"seed", p.seed}}},
          {"scene", s.hysteresis ? friction_scene_json(*s.hysteresis) : contact_scene_json(s.scene)}};
}

namespace {

nlohmann::json run_point_unguarded(const RoughnessSweepSpec& s, int index, MPI_Comm comm, int threads,
                                   const StepListener& on_step) {
  const auto t0 = std::chrono::steady_clock::now();
  const int vi = index / s.realizations, r = index % s.realizations;
  const double value = s.values[std::size_t(vi)];
  SynthParams p = s.base;
  p.seed = s.base.seed + std::uint64_t(r);
  p.threads = threads;
  if (s.parameter == RoughnessParameter::h0) p.h0 = value;
  if (s.parameter == RoughnessParameter::hurst) p.hurst = value;
  if (s.parameter == RoughnessParameter::q1_fraction) p.q1_fraction = value;
  const HeightMap m = synthesize(p).map;
  nlohmann::json rec = {{"index", index},     {"value_index", vi}, {"value", value},
                        {"label", label_of(s.parameter, value)}, {"realization", r}, {"seed", p.seed},
                        {"h0", height_stats(m, threads).sq},     {"rms_slope", rms_slope_finite_difference(m, threads)}};
  const MpdResult mpd = mpd_of_map(m, std::vector<unsigned char>(m.size(), 0), {}, threads);
  rec["mpd"] = mpd.mpd;
  rec["mpd_note"] = mpd.note;
  const double wall_surface = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  if (s.hysteresis) {
    // A skid tester wets the road: the surface at its drained limit (every pool full, the rest
    // run off), with the sealing of the pools; the dry mu stays in the record.
    FillRequest req;
    req.limit = true;
    const FillResult f = fill_water(m, req);
    HeightMap wet = m;
    std::copy(f.water.level.begin(), f.water.level.end(), wet.h.begin());
    rec["coverage"] = f.water.coverage;
    rec["contact"] = hysteresis_contact_record(m, WetSurface{&wet, f.water.coverage}, *s.hysteresis, threads);
    rec["quartic"] = nullptr;
    rec["status"] = "ok";
    rec["message"] = "";
    rec["wall"] = {{"surface", wall_surface}, {"contact", seconds_since(t1)}, {"total", seconds_since(t0)}};
    return rec;
  }
  ContactScene scene = s.scene;
  scene.threads = threads;
  SceneRunHooks hooks;
  hooks.on_step = on_step;
  const SceneResult c = run_contact_scene_caught(m, scene, comm, hooks);
  const NormalCurve curve = normal_curve(c.steps);  // the converged steps before the shear
  rec["contact"] = scene_result_json(c);
  rec["normal_curve"] = {{"sigma_star", curve.sigma_star}, {"area", curve.area}};
  const AreaLoadFits fits = area_load_fits(c.steps);
  rec["quartic"] = fits.quartic ? quartic_json(*fits.quartic) : nlohmann::json(nullptr);
  const bool ok = !c.failed && std::isfinite(c.mu_peak);
  rec["status"] = ok ? "ok" : "failed";
  rec["message"] = ok ? "" : "contact: " + c.message;
  rec["wall"] = {{"surface", wall_surface}, {"contact", seconds_since(t1)}, {"total", seconds_since(t0)}};
  return rec;
}

}  // namespace

nlohmann::json run_roughness_point(const RoughnessSweepSpec& s, int index, MPI_Comm comm, int threads,
                                   const StepListener& on_step) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    return run_point_unguarded(s, index, comm, threads, on_step);
  } catch (const std::exception& e) {  // one failed run must not stop the others (or hang MPI)
    const int vi = index / s.realizations;
    const double value = s.values[std::size_t(vi)];
    return {{"index", index},
            {"value_index", vi},
            {"value", value},
            {"label", label_of(s.parameter, value)},
            {"realization", index % s.realizations},
            {"status", "failed"},
            {"message", e.what()},
            {"wall", {{"total", seconds_since(t0)}}}};
  }
}

nlohmann::json roughness_table(const std::vector<nlohmann::json>& runs) {
  std::map<int, std::vector<const nlohmann::json*>> by_value;
  for (const auto& r : runs) by_value[r["value_index"].get<int>()].push_back(&r);
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [vi, list] : by_value) {
    std::vector<double> mu, ap, an, kappa, h0, slope, mpd, sn, sp;
    std::vector<int> indices;
    int failed = 0;
    for (const nlohmann::json* r : list) {
      indices.push_back((*r)["index"].get<int>());
      if ((*r)["status"] != "ok") {
        ++failed;
        continue;
      }
      const auto& c = (*r)["contact"];
      mu.push_back(c["mu_peak"].get<double>());
      ap.push_back(c["area_at_peak"].get<double>());
      an.push_back(c["area_normal"].get<double>());
      if ((*r)["quartic"].is_object()) kappa.push_back((*r)["quartic"]["kappa"].get<double>());
      h0.push_back((*r)["h0"].get<double>());
      slope.push_back((*r)["rms_slope"].get<double>());
      if ((*r).contains("mpd") && (*r)["mpd"].is_number()) mpd.push_back((*r)["mpd"].get<double>());
      // the wet-at-speed model's skid number and speed constant (hysteresis sweeps with a film);
      // Sp is absent (null) where friction does not fall with speed
      if (c.contains("sp_kmh")) {
        sn.push_back(c["sn"].get<double>());
        if (c["sp_kmh"].is_number()) sp.push_back(c["sp_kmh"].get<double>());
      }
    }
    std::sort(indices.begin(), indices.end());
    const nlohmann::json& first = *list.front();
    rows.push_back({{"value", first["value"]},
                    {"label", first["label"]},
                    {"runs", indices},
                    {"failed", failed},
                    {"mu_peak", sample_statistics(mu)},
                    {"area_at_peak", sample_statistics(ap)},
                    {"area_normal", sample_statistics(an)},
                    {"kappa", sample_statistics(kappa)},
                    {"h0", sample_statistics(h0)},
                    {"rms_slope", sample_statistics(slope)},
                    {"mpd", sample_statistics(mpd)},
                    {"sn", sample_statistics(sn)},
                    {"sp_kmh", sample_statistics(sp)}});
  }
  return rows;
}

nlohmann::json thesis_rows(const std::string& dataset, const std::vector<double>& values) {
  const std::string path = std::string(WETROAD_SHARE_DIR) + "/thesis/roughness-tables.json";
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the thesis's tables");
  nlohmann::json t;
  try {
    t = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("not valid JSON: ") + e.what());
  }
  nlohmann::json rows = nlohmann::json::array();
  if (!t["datasets"].contains(dataset)) return rows;
  const auto& d = t["datasets"][dataset];
  const auto& td = d["table_d"];
  const std::string key = dataset == "A" ? "log10_h0" : d["parameter"].get<std::string>();
  for (double v : values) {
    const double x = dataset == "A" ? std::log10(v) : v;
    for (std::size_t k = 0; k < td[key].size(); ++k) {
      const double tv = td[key][k].get<double>();
      if (std::abs(tv - x) > 0.01 * std::abs(tv)) continue;
      const RoughnessParameter p = dataset == "A"   ? RoughnessParameter::h0
                                   : dataset == "B" ? RoughnessParameter::hurst
                                                    : RoughnessParameter::q1_fraction;
      nlohmann::json row = {{"value", v},        {"label", "thesis " + label_of(p, v)}, {"mu", td["mu"][k]},
                            {"mu_cov", td["mu_cov"][k]}, {"area", td["area"][k]},       {"area_cov", td["area_cov"][k]}};
      if (d.contains("table_c1")) {  // kappa at the nearest log h0 of Table C.1 (its own grid)
        const auto& c1 = d["table_c1"];
        std::size_t best = 0;
        for (std::size_t j = 1; j < c1["log10_h0"].size(); ++j)
          if (std::abs(c1["log10_h0"][j].get<double>() - x) < std::abs(c1["log10_h0"][best].get<double>() - x)) best = j;
        if (std::abs(c1["log10_h0"][best].get<double>() - x) < 0.07) row["kappa"] = c1["kappa"][best];
      }
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace wr
