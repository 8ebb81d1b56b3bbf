#pragma once
// The hysteresis-friction rung of the model ladder as one problem: a surface (and optionally its
// wet surface from `fill`), a compound, a pressure, a temperature and a list of speeds ->
// mu(v) dry, and wet by two sealing models. Used by `wetroad friction`, the sweeps' hysteresis
// model and the report's skid numbers.
//
// Life of a run (each phase timed): spectrum (FFT of the dry map, radial PSD, self-affine fit,
// extension to q1) -> dry mu(v) -> wet spectrum -> wet mu(v), homogeneous and local -> checks.
//
// Sealing of water pools (Persson et al., Nature Materials 3, 882 (2004); the thesis's sec.
// 5.4.2, assumptions A1-A3): the tread seals the water in the road's pools, which then act as
// flat walls. Two models:
//  - homogeneous: mu from the PSD of the wet surface max(h, level) as a whole; above the
//    measured band its spectrum is the dry one times the dry area fraction phi (flat water adds
//    no short-wavelength roughness);
//  - local: the sealed water carries its share of the nominal pressure but, being flat, excites
//    no dissipation; the rubber on the dry patches (area fraction phi) slides over their own
//    roughness, whose spectrum per unit dry area is C_wet / phi (all of the wet surface's
//    power lies in the dry patches and at the water-road edges). So
//    mu_local(v) = phi * mu(C_wet / phi, sigma0, v), and A/A0 = phi P. A PSD of the whole wet
//    surface averages dry and flooded places into one milder roughness, and mu is concave in
//    the roughness (P falls as the roughness grows), so the homogeneous model underestimates
//    the drop; the local one keeps the dry patches' roughness whole. (docs/friction-model.md)
//
// Skid number: SN = 100 mu at 17.9 m/s (ASTM E274's locked wheel at 64 km/h), flash temperature
// as configured.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"
#include "lib/contact/model_ladder.hpp"
#include "lib/core/provenance.hpp"
#include "lib/friction/compound.hpp"
#include "lib/friction/exact_friction.hpp"
#include "lib/friction/hysteresis_friction.hpp"
#include "lib/friction/roughness_spectrum.hpp"
#include "lib/friction/skid_at_speed.hpp"
#include "lib/friction/uncertainty.hpp"

namespace wr {

constexpr double kLockedWheelSpeed = 17.9;  // m/s, 64 km/h (ASTM E274)
// The pressure must stay well below the rubber's rubbery modulus for the theory's small-strain,
// partial-contact picture (design.md's validity check "sigma0 much below the modulus").
constexpr double kMaxPressureToModulus = 0.1;

// Which rung computes mu(v): Persson's mean-field theory (milliseconds, the whole extrapolated
// band), the exact steady sliding on the map (seconds per speed, the map's own band only:
// lib/friction/exact_friction.hpp), or `automatic`: Persson unless one of its model-deciding
// checks fails on a map whose band carries the friction (no extrapolation), then the exact rung.
enum class HysteresisModel { persson, viscoelastic, automatic };
const char* hysteresis_model_name(HysteresisModel m);
// "persson", "viscoelastic" or "auto"; InputError naming `option` otherwise.
HysteresisModel parse_hysteresis_model(const std::string& name, const std::string& option);

struct FrictionScene {
  HysteresisModel model = HysteresisModel::persson;
  std::size_t exact_refine = kDefaultExactRefine;  // the exact rung's grid refinement
  bool progress = false;                           // the exact rung's per-speed lines on stderr
  Compound compound;
  std::string compound_path;     // "" for the built-in default
  FrictionOptions options;       // pressure, temperature, quadrature, flash temperature, threads
  std::optional<double> q1;      // 1/m; absent: max(kDefaultQ1, the map's last resolved wavenumber)
  std::optional<double> q1_rms_slope;  // instead of q1: the rms-slope criterion's slope (q1_for_rms_slope)
  std::vector<double> speeds;    // m/s, > 0
  // Wet friction at speed under a water film (lib/friction/skid_at_speed.hpp); absent: the
  // hysteresis friction of the drained road alone.
  std::optional<FilmScene> film;
  // With a film: the skid number's band and tornado over these input ranges (empty: the
  // defaults of lib/friction/uncertainty.hpp); absent: none.
  std::optional<UncertaintySetup> band;
  bool mpd = true;  // the dry map's MPD (ISO 13473-1) for the report; the sweeps record their own
};

struct FrictionCurve {
  std::string surface;            // "dry", "wet-homogeneous", "wet-local"
  std::vector<FrictionPoint> points;
  double peak_mu = 0, peak_v = 0;
  double sn64 = 0;                // 100 mu at kLockedWheelSpeed (computed even when not in speeds)
  FrictionPoint at_locked_wheel;
};

struct WetSurface {
  const HeightMap* height = nullptr;  // max(h, level), same grid as the dry map
  double coverage = 0;                // fraction of the area under water, [0, 1)
};

struct FrictionRun {
  RadialPsd measured;       // the dry map's radial PSD
  PsdFit fit;               // its self-affine fit
  double nyquist = 0;       // 1/m
  double mpd = 0;           // m: the dry map's mean profile depth (ISO 13473-1, roads/mpd.hpp)
  RoughnessSpectrum dry_spectrum;  // the above, extended to q1
  std::string q1_choice = "default";  // "given", "default", or "rms-slope S"
  FrictionCurve dry;
  std::optional<FrictionCurve> wet_homogeneous, wet_local;
  double coverage = 0;
  // With a film: mu(v) at the scene's speeds and 20-100 km/h, the skid number, Sp, FR60 and the
  // hydroplaning speed; mu_h from the local sealing model's curve when a wet surface is given,
  // else the dry one.
  std::optional<SkidCurve> film;
  std::optional<SkidBand> band;
  std::vector<InputRange> band_ranges;
  std::vector<ValidityCheck> checks;  // pressure vs modulus, unmeasured share, compound origin
  // The rung that computed the curves ("persson" or "viscoelastic") and why it was chosen.
  std::string model = "persson";
  std::string model_reason;
  // With the exact rung: Persson's theory on the same band (the comparison) and the solver's record.
  std::optional<FrictionCurve> persson_same_band;
  std::optional<ExactStats> exact;
  PhaseTimer timer;
};

// InputError naming the option: no speeds, a speed <= 0, the options of check_friction_options,
// the flash temperature asked of a compound without thermal data.
void check_friction_scene(const FrictionScene& s);
// The built-in default compound (share/compounds/synthetic-tread.json).
std::string default_compound_path();

// Runs the scene on `dry` (a 2-D map; its mean plane removed) and optionally its wet surface.
FrictionRun run_friction(const HeightMap& dry, const std::optional<WetSurface>& wet, const FrictionScene& s,
                         const std::string& source);

// mu at `speed` for a list of cut-offs q1 (1/m) on the run's measured spectrum: how much the
// unmeasured scales carry.
std::vector<std::pair<double, double>> mu_against_q1(const FrictionRun& r, const FrictionScene& s, double speed,
                                                     const std::vector<double>& q1s, const std::string& source);

nlohmann::json friction_curve_json(const FrictionCurve& c);
// {test, source, patch_length, drainage_length, slip_speed, water_film, viscosity, critical_contact,
//  sn, sp_kmh (null: mu does not fall with speed), sp_fit_rms, fr60, hydroplaning_kmh (null: none),
//  at_test {...}, squeeze_at_test [{t, separation, asperity_pressure, contact}] (u(t) at the
//  test's speed), speeds [...], skid [...]}, each point {v, mu, mu_hysteresis, mu_viscous,
//  load_share, patch_time, drain_time, contact_time, equilibrium_separation, equilibrium_contact,
//  final_separation, trapped}.
nlohmann::json skid_curve_json(const SkidCurve& c, const FilmScene& film, double temperature);
// {nominal, p05, p95, min, max, samples, evaluations, ranges [{name, low, high}], tornado [{name,
//  low, high, sn_low, sn_high}]}.
nlohmann::json skid_band_json(const SkidBand& b, const std::vector<InputRange>& ranges);
// {model: "hysteresis", mechanism, valid, checks: [{check, passed, detail}]}.
nlohmann::json hysteresis_validity_json(const std::vector<ValidityCheck>& checks);
// The JSON of `wetroad friction` (SI units): model, compound, temperature, pressure, q0, q1,
// q_measured, extrapolated, flash_temperature, speeds [...], peak, sn64, wet {...}, checks.
nlohmann::json friction_run_json(const FrictionRun& r, const FrictionScene& s);

}  // namespace wr
