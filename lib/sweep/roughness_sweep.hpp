#pragma once
// The roughness sweeps of the thesis (sec. 5.3, Tables C.1 and D.1-D.3): friction and contact
// area of the shear test, and the normal-load curve's quartic fit (eq. 5.4, kappa), over one
// surface parameter with R independent synthetic realizations per value.
//
// Datasets (Table 5.1; 300 x 300 over 3 cm, q0 = 5 qL, q1 = the grid's Nyquist wavenumber):
//   A: h0 = 10^-4.14 ... 10^-3.14 m (Table D.1's nine values), H = 0.7;
//   B: H = 0.5 ... 0.9, h0 = 0.71 mm;
//   C: q1 / q1hat = 1/8, 1/4, 1/2, 1 (low-pass, h0 drops slightly), h0 = 0.71 mm, H = 0.7.
// Run index = value index * R + realization; realization r uses seed base seed + r, the same
// seeds for every value (as the thesis's datasets vary one parameter of the same surfaces).
//
// Run record (JSON): index, value_index, value, realization, seed, h0 (measured rms height), rms_slope,
// mpd (ISO 13473-1 over the map, with mpd_note when its baseline or filter departs from it),
// status, message, contact {model, mu_peak, ux_peak, area_at_peak, area_normal, fz_normal,
// failed, message, unknowns, steps [...], validity}, normal_curve {sigma_star, area},
// quartic {Pi, Omega, Lambda, kappa, r2} (null with fewer than 4 normal steps or a singular fit),
// wall {surface, contact, total}.
#include <mpi.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/scene/contact_scene.hpp"
#include "lib/friction/friction_scene.hpp"
#include "roads/synthesize.hpp"

namespace wr {

enum class RoughnessParameter { h0, hurst, q1_fraction };

struct RoughnessSweepSpec {
  std::string dataset = "A";  // "A", "B", "C" (thesis presets) or "custom"
  RoughnessParameter parameter = RoughnessParameter::h0;
  std::vector<double> values;
  SynthParams base;           // the surface's other parameters; seed of realization 0
  int realizations = 10;
  ContactScene scene;                     // the contact models (fem, spectral) ...
  std::optional<FrictionScene> hysteresis;  // ... or the hysteresis model at its one speed
};

const char* parameter_name(RoughnessParameter p);  // "h0", "hurst", "q1_fraction"
// The thesis's dataset `name` (A, B, C) with its values and surface; throws InputError otherwise.
RoughnessSweepSpec roughness_dataset(const std::string& name);

// Throws InputError naming the option at fault.
void check_roughness_spec(const RoughnessSweepSpec& s);
nlohmann::json roughness_spec_json(const RoughnessSweepSpec& s);
int roughness_run_count(const RoughnessSweepSpec& s);

// One run: synthesize the realization at its value, run the contact scene, fit the normal curve.
// With the hysteresis model: fill the surface to its drained limit (as a skid tester leaves the
// road) and record the wet mu at the scene's speed (mu_peak: local sealing) beside the dry one.
// Never throws: an exception becomes a failed record with the key fields and the reason.
// `on_step` (may be empty) hears of every load step of the contact run as it ends.
nlohmann::json run_roughness_point(const RoughnessSweepSpec& s, int index, MPI_Comm comm, int threads,
                                   const StepListener& on_step = {});

// One row per value: mean, std, ci95 and cov (std / mean, the thesis's s*) of mu_peak,
// area_at_peak, area_normal, kappa, h0 and rms_slope over the finished realizations; n, failed,
// runs. Rows carry "value" and "label" (e.g. "h0 = 0.305 mm").
nlohmann::json roughness_table(const std::vector<nlohmann::json>& runs);

// The thesis's rows for `dataset` next to this sweep's (share/thesis/roughness-tables.json,
// matched by value within 1 %): per row {value, label, mu, mu_cov, area, area_cov[, kappa]}; rows
// without a thesis counterpart are left out. Throws InputError when the file cannot be read.
nlohmann::json thesis_rows(const std::string& dataset, const std::vector<double>& values);

}  // namespace wr
