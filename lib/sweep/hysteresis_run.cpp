#include "lib/sweep/hysteresis_run.hpp"

#include <cmath>

namespace wr {

nlohmann::json friction_scene_json(const FrictionScene& s) {
  return {{"model", "hysteresis"},
          {"hysteresis_model", hysteresis_model_name(s.model)},
          {"exact_refine", s.exact_refine},
          {"compound", compound_to_json(s.compound)},
          {"compound_path", s.compound_path},
          {"pressure", s.options.pressure},
          {"temperature", s.options.temperature},
          {"points_per_decade", s.options.points_per_decade},
          {"flash_temperature", s.options.flash_temperature},
          {"q1", s.q1 ? nlohmann::json(*s.q1) : nlohmann::json(nullptr)},
          {"q1_rms_slope", s.q1_rms_slope ? nlohmann::json(*s.q1_rms_slope) : nlohmann::json(nullptr)},
          {"speeds", s.speeds},
          {"film", s.film ? nlohmann::json{{"test", s.film->test.name},
                                           {"source", s.film->test.source},
                                           {"patch_length", s.film->test.patch_length},
                                           {"drainage_length", s.film->test.drainage_length},
                                           {"slip_speed", s.film->test.slip_speed},
                                           {"water_film", s.film->test.water_film},
                                           {"critical_contact", s.film->critical_contact}}
                          : nlohmann::json(nullptr)},
          {"band", s.band.has_value()}};
}

nlohmann::json hysteresis_contact_record(const HeightMap& ground, const std::optional<WetSurface>& wet,
                                         const FrictionScene& s, int threads) {
  FrictionScene scene = s;
  scene.options.threads = threads;
  scene.mpd = false;  // the sweep measures the surface's MPD itself
  scene.speeds = {s.speeds.front(), kIfiLowSpeed};
  const bool has_water = wet && wet->coverage > 0;
  const FrictionRun r = run_friction(ground, has_water ? wet : std::nullopt, scene, "sweep surface");
  const FrictionPoint& dry = r.dry.points.front();
  const FrictionPoint& hom = has_water ? r.wet_homogeneous->points.front() : dry;
  const FrictionPoint& loc = has_water ? r.wet_local->points.front() : dry;
  const FrictionPoint& low = has_water ? r.wet_local->points.back() : r.dry.points.back();
  nlohmann::json rec = {{"model", "hysteresis"},
          {"speed", dry.v},
          {"mu_peak", loc.mu},
          {"mu_dry", dry.mu},
          {"mu_homogeneous", hom.mu},
          {"mu_local", loc.mu},
          {"sn", 100 * loc.mu},
          {"mu_low_speed", low.mu},
          {"low_speed", kIfiLowSpeed},
          {"area_at_peak", loc.area_fraction},
          {"area_normal", loc.area_fraction},
          {"temperature_rise", loc.temperature_rise},
          {"q1", r.dry_spectrum.q_end},
          {"q1_choice", r.q1_choice},
          {"extrapolated", r.dry_spectrum.extrapolated()},
          {"failed", false},
          {"message", ""},
          {"validity", hysteresis_validity_json(r.checks)},
          {"rung", r.model},
          {"rung_chosen_by", r.model_reason}};
  if (r.exact) rec["mu_persson_same_band"] = r.persson_same_band->points.front().mu;
  if (r.film) {
    // Under the film: mu at the sweep's speed and at 20 km/h are the wet friction at speed; the
    // drained road's hysteresis friction stays as mu_drained.
    const SkidCurve& f = *r.film;
    rec["mu_drained"] = loc.mu;
    rec["mu_peak"] = f.points.front().mu;
    rec["mu_low_speed"] = f.points.back().mu;
    rec["sn"] = f.sn;
    rec["sn_speed"] = f.at_test.v;
    rec["sp_kmh"] = std::isfinite(f.sp_kmh) ? nlohmann::json(f.sp_kmh) : nlohmann::json(nullptr);
    rec["fr60"] = f.fr60;
    rec["hydroplaning_kmh"] = std::isfinite(f.hydroplaning_kmh) ? nlohmann::json(f.hydroplaning_kmh) : nlohmann::json(nullptr);
    rec["load_share"] = f.at_test.load_share;
    rec["drain_time"] = std::isfinite(f.at_test.drain_time) ? nlohmann::json(f.at_test.drain_time) : nlohmann::json(nullptr);
    rec["patch_time"] = f.at_test.patch_time;
    nlohmann::json sn_v = nlohmann::json::array();
    for (const FilmPoint& p : f.skid) sn_v.push_back({p.v * 3.6, 100 * p.mu});
    rec["sn_against_speed"] = sn_v;  // [[km/h, SN], ...]
    if (r.band) rec["sn_band"] = {{"p05", r.band->p05}, {"p95", r.band->p95}, {"min", r.band->min}, {"max", r.band->max}};
  }
  return rec;
}

}  // namespace wr
