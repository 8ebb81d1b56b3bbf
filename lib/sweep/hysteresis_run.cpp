#include "lib/sweep/hysteresis_run.hpp"

namespace wr {

nlohmann::json friction_scene_json(const FrictionScene& s) {
  return {{"model", "hysteresis"},
          {"compound", compound_to_json(s.compound)},
          {"compound_path", s.compound_path},
          {"pressure", s.options.pressure},
          {"temperature", s.options.temperature},
          {"points_per_decade", s.options.points_per_decade},
          {"flash_temperature", s.options.flash_temperature},
          {"q1", s.q1 ? nlohmann::json(*s.q1) : nlohmann::json(nullptr)},
          {"speeds", s.speeds}};
}

nlohmann::json hysteresis_contact_record(const HeightMap& ground, const std::optional<WetSurface>& wet,
                                         const FrictionScene& s, int threads) {
  FrictionScene scene = s;
  scene.options.threads = threads;
  scene.speeds = {s.speeds.front(), kIfiLowSpeed};
  const bool has_water = wet && wet->coverage > 0;
  const FrictionRun r = run_friction(ground, has_water ? wet : std::nullopt, scene, "sweep surface");
  const FrictionPoint& dry = r.dry.points.front();
  const FrictionPoint& hom = has_water ? r.wet_homogeneous->points.front() : dry;
  const FrictionPoint& loc = has_water ? r.wet_local->points.front() : dry;
  const FrictionPoint& low = has_water ? r.wet_local->points.back() : r.dry.points.back();
  return {{"model", "hysteresis"},
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
          {"extrapolated", r.dry_spectrum.extrapolated()},
          {"failed", false},
          {"message", ""},
          {"validity", hysteresis_validity_json(r.checks)}};
}

}  // namespace wr
