#pragma once
// The hysteresis rung inside the sweeps: a run's "contact" record computed by Persson's
// hysteresis friction (lib/friction/friction_scene.hpp) instead of a contact scene, so that
// sweep-coverage and sweep-roughness, their tables, checkpoints and charts serve both models.
//
// Record: {model: "hysteresis", speed, mu_peak (the friction at `speed`: on a wet surface the
// local sealing model's, design choice of docs/friction-model.md), mu_dry, mu_homogeneous,
// mu_local, mu_low_speed (the same at kIfiLowSpeed, for the report's IFI route), area_at_peak and area_normal (A/A0 at q1), temperature_rise, sn, q1, extrapolated,
// failed: false, message: "", validity}.
#include <optional>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"
#include "lib/friction/friction_scene.hpp"

namespace wr {

// The low slip speed of the IFI route (ASTM E1960's DFT speed, 20 km/h).
constexpr double kIfiLowSpeed = 20 / 3.6;  // m/s

// The scene as a sweep spec stores it (compared on --resume): the compound's content, not
// only its path, so an edited compound file cannot mix into a resumed sweep.
nlohmann::json friction_scene_json(const FrictionScene& s);

// `wet` absent (or coverage 0): the dry surface. Throws what run_friction throws.
nlohmann::json hysteresis_contact_record(const HeightMap& ground, const std::optional<WetSurface>& wet,
                                         const FrictionScene& s, int threads);

}  // namespace wr
