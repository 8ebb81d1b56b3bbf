#include "lib/core/provenance.hpp"
#include "lib/sweep/coverage_sweep.hpp"
#include "lib/sweep/sweep_engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "lib/core/errors.hpp"
#include "lib/sweep/hysteresis_run.hpp"
#include "lib/sweep/sample_statistics.hpp"
#include "roads/height_stats.hpp"
#include "roads/mpd.hpp"
#include "roads/spectrum.hpp"
#include "roads/surface_import.hpp"

namespace wr {

void check_sweep_spec(const CoverageSweepSpec& s) {
  if (s.coverages.empty()) throw InputError("--coverages", "give at least one coverage");
  for (std::size_t i = 0; i < s.coverages.size(); ++i) {
    const double c = s.coverages[i];
    if (!(c >= 0 && c < 1)) throw InputError("--coverages", "each coverage must be a fraction in [0, 1)");
    if (i > 0 && !(c > s.coverages[i - 1])) throw InputError("--coverages", "coverages must be ascending and distinct");
  }
  check_realizations(s.realizations, s.synth ? s.synth->seed : 0);
  if (s.realizations > 1 && !s.synth) throw InputError("--realizations", "only synthetic surfaces have realizations");
  if (!s.synth && s.surface_path.empty()) throw InputError("--surface", "give a surface file or synthesis options");
  if (s.synth) validate(*s.synth);  // now, not when the first run starts
  if (s.connectivity != 4 && s.connectivity != 8) throw InputError("--connectivity", "must be 4 or 8");
  if (s.hysteresis) check_friction_scene(*s.hysteresis);
  else check_contact_scene(s.scene);
}

std::vector<CoverageRunKey> plan_runs(const CoverageSweepSpec& s) {
  std::vector<CoverageRunKey> keys;
  for (int r = 0; r < s.realizations; ++r)
    for (double c : s.coverages) keys.push_back({int(keys.size()), r, c});
  return keys;
}

nlohmann::json sweep_spec_json(const CoverageSweepSpec& s) {
  nlohmann::json j = {{"coverages", s.coverages},
                      {"realizations", s.realizations},
                      {"scene", s.hysteresis ? friction_scene_json(*s.hysteresis) : contact_scene_json(s.scene)},
                      {"tiling", s.tiling == Tiling::torus ? "torus" : "3x3"},
                      {"connectivity", s.connectivity}};
  if (s.synth) {
    const SynthParams& p = *s.synth;
    j["surface"] = {{"synthetic", true}, {"nx", p.nx},   {"ny", p.ny},       {"dx", p.dx},
                    {"h0", p.h0},        {"hurst", p.hurst}, {"q0_ratio", p.q0_ratio},
                    {"q1", p.q1 ? nlohmann::json(*p.q1) : nlohmann::json(nullptr)},
                    {"q1_fraction", p.q1_fraction}, {"oversample", p.oversample},
                    {"sampling", sampling_name(p.sampling)}, {"seed", p.seed}};
  } else {
    j["surface"] = {{"synthetic", false}, {"path", s.surface_path}};
  }
  return j;
}

CoverageRunner::CoverageRunner(const CoverageSweepSpec& spec, MPI_Comm contact_comm, int threads)
    : spec_(spec), comm_(contact_comm), threads_(threads) {}

void CoverageRunner::load_realization(int r) {
  if (r == loaded_) return;
  const auto t0 = std::chrono::steady_clock::now();
  if (spec_.synth) {
    SynthParams p = *spec_.synth;
    p.seed = spec_.synth->seed + std::uint64_t(r);
    p.threads = threads_;
    ground_ = synthesize(p).map;
    seed_ = p.seed;
  } else {
    LoadedSurface s = load_surface(spec_.surface_path);
    require_periodic_map(s, "the contact scene repeats the surface");
    ground_ = std::move(s.map);
    seed_ = 0;
  }
  FillRequest lim;
  lim.limit = true;
  lim.tiling = spec_.tiling;
  lim.connectivity = spec_.connectivity;
  drained_limit_ = fill_water(ground_, lim).water.coverage;
  const MpdResult mpd = mpd_of_map(ground_, std::vector<unsigned char>(ground_.size(), 0), {}, threads_);
  ground_mpd_ = mpd.mpd;
  ground_mpd_note_ = mpd.note;
  wall_surface_ = seconds_since(t0);
  loaded_ = r;
}

nlohmann::json CoverageRunner::run(const CoverageRunKey& key, const StepListener& on_step) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    return run_unguarded(key, on_step);
  } catch (const std::exception& e) {  // one failed run must not stop the others (or hang MPI)
    return {{"index", key.index}, {"realization", key.realization}, {"target", key.target}, {"status", "failed"},
            {"message", e.what()}, {"wall", {{"total", seconds_since(t0)}}}};
  }
}

nlohmann::json CoverageRunner::run_unguarded(const CoverageRunKey& key,
                                             const StepListener& on_step) {
  const auto t0 = std::chrono::steady_clock::now();
  load_realization(key.realization);
  nlohmann::json rec = {{"index", key.index}, {"realization", key.realization}, {"seed", seed_},
                        {"target", key.target}, {"drained_limit", drained_limit_},
                        {"ground_mpd", ground_mpd_}, {"ground_mpd_note", ground_mpd_note_}};
  HeightMap wet = ground_;
  const auto t_water = std::chrono::steady_clock::now();
  if (key.target == 0) {
    rec.update({{"water", "dry"}, {"coverage", 0.0}, {"rain_depth", 0.0}, {"mean_pool_depth", 0.0},
                {"max_pool_depth", 0.0}, {"stored_volume", 0.0}, {"lakes", 0}});
  } else {
    FillRequest req;
    req.coverage = key.target;
    // Up to the drained limit the water runs off through the periodic surface; beyond it only
    // standing (stagnant) water reaches the target (thesis Figure 5.25).
    req.mode = key.target <= drained_limit_ ? WaterMode::drained : WaterMode::stagnant;
    req.tiling = spec_.tiling;
    req.connectivity = spec_.connectivity;
    try {
      const FillResult f = fill_water(ground_, req);
      std::copy(f.water.level.begin(), f.water.level.end(), wet.h.begin());
      rec.update({{"water", req.mode == WaterMode::drained ? "drained" : "stagnant"},
                  {"coverage", f.water.coverage},
                  {"rain_depth", f.water.rain_depth},
                  {"mean_pool_depth", f.water.mean_depth},
                  {"max_pool_depth", f.water.max_depth},
                  {"stored_volume", f.water.stored_volume},
                  {"lakes", f.water.lakes}});
    } catch (const InputError& e) {
      rec.update({{"status", "failed"}, {"message", std::string("water: ") + e.what()}});
      rec["wall"] = {{"surface", wall_surface_}, {"water", seconds_since(t_water)}, {"contact", 0.0},
                     {"total", seconds_since(t0)}};
      return rec;
    }
  }
  const double wall_water = seconds_since(t_water);
  // The wet surface's own texture (Figure 5.26): pools flatten it.
  const SpectrumResult sp = analyze_spectrum(wet, threads_);
  rec["wet_sq"] = height_stats(wet, threads_).sq;
  rec["wet_rms_slope"] = rms_slope_finite_difference(wet, threads_);
  rec["psd"] = {{"q", sp.psd.q}, {"C", sp.psd.C}};

  const auto t_contact = std::chrono::steady_clock::now();
  if (spec_.hysteresis) {
    const double coverage = rec["coverage"].get<double>();
    rec["contact"] = hysteresis_contact_record(ground_, WetSurface{&wet, coverage}, *spec_.hysteresis, threads_);
    rec["status"] = "ok";
    rec["message"] = "";
    rec["wall"] = {{"surface", wall_surface_}, {"water", wall_water}, {"contact", seconds_since(t_contact)},
                   {"total", seconds_since(t0)}};
    return rec;
  }
  ContactScene scene = spec_.scene;
  scene.threads = threads_;
  // One penetration tolerance for the whole sweep: the ground's (ContactScene::max_penetration).
  if (scene.max_penetration == 0) scene.max_penetration = default_max_penetration(ground_, threads_);
  SceneRunHooks hooks;
  hooks.on_step = on_step;
  const SceneResult c = run_contact_scene_caught(wet, scene, comm_, hooks);
  rec["contact"] = scene_result_json(c);
  const bool ok = !c.failed && std::isfinite(c.mu_peak);
  rec["status"] = ok ? "ok" : "failed";
  rec["message"] = ok ? "" : "contact: " + c.message;
  rec["wall"] = {{"surface", wall_surface_}, {"water", wall_water}, {"contact", seconds_since(t_contact)},
                 {"total", seconds_since(t0)}};
  return rec;
}

namespace {

double get_number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::numeric_limits<double>::quiet_NaN();
}

// The friction the ratios compare: the drained road's (the hysteresis model under a film keeps it
// as mu_drained beside its friction at speed, mu_peak), so that mu_ratio is the sealing's effect
// of the coverage alone (the thesis's Figure 5.25) and comparable with mu_ratio_homogeneous.
double ratio_friction(const nlohmann::json& contact) {
  return contact.contains("mu_drained") ? contact["mu_drained"].get<double>() : contact["mu_peak"].get<double>();
}

}  // namespace

nlohmann::json coverage_table(const std::vector<nlohmann::json>& runs) {
  // Dry friction per realization: the reference of mu_ratio.
  std::map<int, double> mu_dry;
  for (const auto& r : runs)
    if (r.value("target", -1.0) == 0 && r.value("status", "") == "ok")
      mu_dry[r["realization"].get<int>()] = ratio_friction(r["contact"]);
  std::map<double, std::vector<const nlohmann::json*>> by_target;
  for (const auto& r : runs) by_target[r["target"].get<double>()].push_back(&r);
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [target, list] : by_target) {
    std::vector<double> mu, ratio, ratio_hom, area_peak, area_normal, coverage, pool, sq;
    std::vector<int> indices;
    std::string water;
    int failed = 0;
    for (const nlohmann::json* r : list) {
      indices.push_back((*r)["index"].get<int>());
      if (r->value("status", "") != "ok") {
        ++failed;
        continue;
      }
      water = (*r)["water"].get<std::string>();
      mu.push_back((*r)["contact"]["mu_peak"].get<double>());
      // A ratio to a dry friction that is not positive means nothing (a scene without friction).
      const auto d = mu_dry.find((*r)["realization"].get<int>());
      if (d != mu_dry.end() && d->second > 0) ratio.push_back(ratio_friction((*r)["contact"]) / d->second);
      if (d != mu_dry.end() && d->second > 0 && (*r)["contact"].contains("mu_homogeneous"))
        ratio_hom.push_back((*r)["contact"]["mu_homogeneous"].get<double>() / d->second);
      area_peak.push_back(get_number((*r)["contact"], "area_at_peak"));
      area_normal.push_back(get_number((*r)["contact"], "area_normal"));
      coverage.push_back(get_number(*r, "coverage"));
      pool.push_back(get_number(*r, "mean_pool_depth"));
      sq.push_back(get_number(*r, "wet_sq"));
    }
    std::sort(indices.begin(), indices.end());
    rows.push_back({{"target", target},
                    {"water", water},
                    {"label", water},
                    {"runs", indices},
                    {"failed", failed},
                    {"mu_peak", sample_statistics(mu)},
                    {"mu_ratio", sample_statistics(ratio)},
                    {"mu_ratio_homogeneous", sample_statistics(ratio_hom)},
                    {"area_at_peak", sample_statistics(area_peak)},
                    {"area_normal", sample_statistics(area_normal)},
                    {"coverage", sample_statistics(coverage)},
                    {"mean_pool_depth", sample_statistics(pool)},
                    {"wet_sq", sample_statistics(sq)}});
  }
  return rows;
}

}  // namespace wr
