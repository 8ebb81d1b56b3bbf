#include "lib/friction/friction_scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"
#include "roads/mpd.hpp"
#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"

namespace wr {
namespace {


// The scene's speeds plus the locked-wheel point.
std::vector<double> curve_speeds(const FrictionScene& s) {
  std::vector<double> speeds = s.speeds;
  speeds.push_back(kLockedWheelSpeed);
  return speeds;
}

// A curve from its points at curve_speeds(s): the locked-wheel point, the peak and skid number.
FrictionCurve curve_from(const std::string& surface, std::vector<FrictionPoint> pts) {
  FrictionCurve c;
  c.surface = surface;
  c.at_locked_wheel = pts.back();
  pts.pop_back();
  c.points = std::move(pts);
  c.sn64 = 100 * c.at_locked_wheel.mu;
  for (const FrictionPoint& p : c.points)
    if (p.mu > c.peak_mu) {
      c.peak_mu = p.mu;
      c.peak_v = p.v;
    }
  return c;
}

// Persson's curve at the scene's speeds plus the locked-wheel point, its peak and skid number.
FrictionCurve curve(const std::string& surface, const RoughnessSpectrum& psd, const FrictionScene& s,
                    double mu_scale, double area_scale) {
  std::vector<FrictionPoint> pts = friction_curve(psd, s.compound, curve_speeds(s), s.options);
  for (FrictionPoint& p : pts) {
    p.mu *= mu_scale;
    p.mu_extrapolated *= mu_scale;
    p.area_fraction *= area_scale;
  }
  return curve_from(surface, std::move(pts));
}

std::vector<ValidityCheck> scene_checks(const FrictionRun& r, const FrictionScene& s) {
  std::vector<ValidityCheck> checks;
  const double ratio = s.options.pressure / s.compound.e_relaxed;
  if (r.exact) {
    const ExactStats& e = *r.exact;
    checks.push_back({"steady sliding converged at every speed", e.converged,
                      (e.converged ? std::string("") : e.message + "; ") + std::to_string(e.nx) + "x" + std::to_string(e.ny) +
                          " grid (map x" + std::to_string(e.refine) + "), at most " + std::to_string(e.max_iterations) +
                          " iterations, dissipation identity within " + number_text(e.max_identity_residual),
                      false});
    const double pe = r.persson_same_band->at_locked_wheel.mu, ex = r.dry.at_locked_wheel.mu;
    checks.push_back({"Persson's theory on the same band within 20 %", std::abs(pe / ex - 1) <= 0.2,
                      "mu at 17.9 m/s: Persson " + number_text(pe) + ", exact " + number_text(ex) + " (ratio " +
                          number_text(pe / ex) + ")",
                      false});
  } else {
    checks.push_back({"pressure well below the rubbery modulus", ratio <= kMaxPressureToModulus,
                      "sigma0 / E_r = " + number_text(ratio) + " (limit " + number_text(kMaxPressureToModulus) + ")", true});
  }
  const FrictionPoint& lw = r.dry.at_locked_wheel;
  const double share = lw.mu > 0 ? lw.mu_extrapolated / lw.mu : 0;
  checks.push_back({"measured band carries most of the friction", share <= 0.5,
                    r.dry_spectrum.extrapolated()
                        ? "scales above the measured band (q > " + number_text(r.dry_spectrum.q_measured) + " 1/m, up to q1 = " +
                              number_text(r.dry_spectrum.q_end) + " 1/m) carry " + number_text(100 * share) + " % of mu at 17.9 m/s"
                        : "no extrapolation: q1 = " + number_text(r.dry_spectrum.q_end) + " 1/m lies in the measured band",
                    false});
  if (r.film) {
    const double a = r.film->at_test.equilibrium_contact;
    checks.push_back({"mean-field drainage valid", a <= kMeanFieldFlowMaxContact,
                      "A/A0 " + number_text(a) + " at sigma0 and the test's speed (the effective medium's flow is within a "
                      "factor 1.6 of the map's up to " + number_text(kMeanFieldFlowMaxContact) +
                      "; above, near percolation, check the drainage with `wetroad flow`)",
                      false});
  }
  checks.push_back({"compound fitted to a measured master curve", !s.compound.synthetic,
                    s.compound.synthetic ? "SYNTHETIC compound \"" + s.compound.name + "\": trends, not a prediction for a real tyre"
                                         : "\"" + s.compound.name + "\" (" + s.compound.source + ")",
                    false});
  return checks;
}

void check_wet_grid(const HeightMap& dry, const WetSurface& wet, const std::string& source) {
  if (wet.height->nx != dry.nx || wet.height->ny != dry.ny)
    throw InputError(source, "the wet surface's grid differs from the dry surface's");
  if (!(wet.coverage >= 0 && wet.coverage < 1)) throw InputError(source, "water coverage must lie in [0, 1)");
}

// The record of more solves of the exact rung added to `into`.
void merge_exact_stats(ExactStats& into, const ExactStats& more) {
  if (into.converged && !more.converged) into.message = more.message;
  into.converged = into.converged && more.converged;
  into.max_iterations = std::max(into.max_iterations, more.max_iterations);
  into.max_identity_residual = std::max(into.max_identity_residual, more.max_identity_residual);
  into.wall_s += more.wall_s;
  into.solves += more.solves;
}

// Decides the rung (FrictionRun::model, model_reason); true for the exact one. The exact rung
// has no sealing models, no flash temperature and no band (yet): asked for with them, it is
// refused; `automatic` keeps Persson then.
bool choose_rung(FrictionRun& r, const FrictionScene& s, bool wet) {
  (void)wet;  // the exact rung slides over the sealed wet surface itself
  const char* missing = s.options.flash_temperature ? "--flash-temperature" : s.band ? "--band" : nullptr;
  if (s.model == HysteresisModel::viscoelastic) {
    if (missing)
      throw InputError(missing, std::string("not with --model viscoelastic: the exact rung is isothermal and has no band yet "
                                            "(use --model persson)"));
    r.model = "viscoelastic";
    r.model_reason = "asked (--model viscoelastic)";
    return true;
  }
  if (s.model == HysteresisModel::persson) {
    r.model_reason = "asked (--model persson)";
    return false;
  }
  const double ratio = s.options.pressure / s.compound.e_relaxed;
  if (ratio <= kMaxPressureToModulus) {
    r.model_reason = "auto: Persson's model-deciding check (pressure well below the rubbery modulus) passes";
    return false;
  }
  if (r.dry_spectrum.extrapolated() || missing) {
    r.model_reason = std::string("auto: Persson's pressure check fails, but ") +
                     (missing ? std::string(missing) + " needs Persson's model"
                              : "q1 lies above the map's band, which is all the exact rung sees") +
                     ": Persson kept, flagged";
    return false;
  }
  r.model = "viscoelastic";
  r.model_reason = "auto: Persson's pressure check fails (sigma0 / E_r = " + number_text(ratio) +
                   ") and the map's band carries the friction: the exact rung";
  return true;
}

}  // namespace

const char* hysteresis_model_name(HysteresisModel m) {
  switch (m) {
    case HysteresisModel::persson: return "persson";
    case HysteresisModel::viscoelastic: return "viscoelastic";
    case HysteresisModel::automatic: return "auto";
  }
  return "?";
}

HysteresisModel parse_hysteresis_model(const std::string& name, const std::string& option) {
  if (name == "persson") return HysteresisModel::persson;
  if (name == "viscoelastic") return HysteresisModel::viscoelastic;
  if (name == "auto") return HysteresisModel::automatic;
  throw InputError(option, "\"" + name + "\": give persson (Persson's theory), viscoelastic (exact steady sliding on the map) or auto");
}

std::string default_compound_path() { return std::string(WETROAD_SHARE_DIR) + "/compounds/synthetic-tread.json"; }

void check_friction_scene(const FrictionScene& s) {
  if (s.speeds.empty()) throw InputError("--speeds", "give at least one sliding speed");
  for (double v : s.speeds)
    if (!(v > 0 && std::isfinite(v))) throw InputError("--speeds", "a sliding speed must be positive (m/s), got " + number_text(v));
  check_friction_options(s.options, s.compound);
  if (s.options.flash_temperature && !s.compound.thermal)
    throw InputError("--flash-temperature", "the compound \"" + s.compound.name +
                                                "\" has no \"thermal\" block (density, specific heat, conductivity)");
  if (s.q1 && !(*s.q1 > 0 && std::isfinite(*s.q1))) throw InputError("--q1", "must be a positive wavenumber in 1/m");
  if (s.q1 && s.q1_rms_slope) throw InputError("--q1", "give a wavenumber or a criterion, not both");
}

FrictionRun run_friction(const HeightMap& dry, const std::optional<WetSurface>& wet, const FrictionScene& s,
                         const std::string& source) {
  check_friction_scene(s);
  if (dry.is_profile()) throw InputError(source, "the hysteresis model needs a 2-D map (an isotropic PSD), not a profile");
  FrictionRun r;
  r.timer.start("spectrum");
  SpectrumResult sp = analyze_spectrum(dry, s.options.threads);
  r.measured = std::move(sp.psd);
  r.nyquist = sp.nyquist;
  r.fit = fit_self_affine(r.measured, r.nyquist, false);
  if (s.mpd) r.mpd = mpd_of_map(dry, std::vector<unsigned char>(dry.size(), 0), {}, s.options.threads).mpd;
  std::optional<double> q1 = s.q1;
  if (s.q1_rms_slope) {
    q1 = q1_for_rms_slope(r.measured, r.nyquist, r.fit, *s.q1_rms_slope, source, "--q1");
    r.q1_choice = "rms-slope " + number_text(*s.q1_rms_slope);
  } else if (s.q1) {
    r.q1_choice = "given";
  }
  r.dry_spectrum = spectrum_from_psd(r.measured, r.nyquist, r.fit, q1, source);
  const bool exact = choose_rung(r, s, wet.has_value());
  if (exact && r.dry_spectrum.extrapolated()) {
    if (s.q1 || s.q1_rms_slope)
      throw InputError("--q1", "the viscoelastic model slides over the map itself, whose band ends at " +
                                   number_text(r.dry_spectrum.q_measured) + " 1/m; give --q1 at or below it, or --model persson");
    r.dry_spectrum = spectrum_from_psd(r.measured, r.nyquist, r.fit, r.dry_spectrum.q_measured, source);
    r.q1_choice = "the map's band";
  }
  std::function<std::vector<double>(const std::vector<double>&)> exact_mu;  // mu_h(v) by the exact rung
  if (exact) {
    r.timer.start("dry mu(v), exact rung");
    ExactStats st;
    r.dry = curve_from("dry", exact_friction_curve(dry, r.dry_spectrum.q_end, s.exact_refine, s.compound, s.options,
                                                   curve_speeds(s), st, s.progress));
    r.exact = st;
    if (wet) {
      // The sealed pools as flat rigid walls (the sealing's assumptions A1-A3, solved): one exact
      // answer where Persson's theory needs two models, so both wet curves hold it.
      check_wet_grid(dry, *wet, source);
      r.coverage = wet->coverage;
      r.timer.start("wet mu(v), exact rung");
      ExactStats ws;
      r.wet_homogeneous = curve_from("wet-sealed", exact_friction_curve(*wet->height, r.dry_spectrum.q_end, s.exact_refine,
                                                                        s.compound, s.options, curve_speeds(s), ws, s.progress));
      r.wet_local = r.wet_homogeneous;
      merge_exact_stats(*r.exact, ws);
    }
    const HeightMap& hyst_map = wet ? *wet->height : dry;
    exact_mu = [&](const std::vector<double>& v) {
      std::vector<double> mu;
      ExactStats more;
      for (const FrictionPoint& p : exact_friction_curve(hyst_map, r.dry_spectrum.q_end, s.exact_refine, s.compound, s.options, v,
                                                         more, s.progress))
        mu.push_back(p.mu);
      merge_exact_stats(*r.exact, more);
      return mu;
    };
    r.timer.start("dry mu(v), Persson on the same band");
    r.persson_same_band = curve("dry", r.dry_spectrum, s, 1.0, 1.0);
  } else {
    r.timer.start("dry mu(v)");
    r.dry = curve("dry", r.dry_spectrum, s, 1.0, 1.0);
  }
  std::optional<RoughnessSpectrum> sealed;  // the local sealing model's spectrum
  if (wet && !exact) {
    check_wet_grid(dry, *wet, source);
    r.coverage = wet->coverage;
    const double phi = 1 - wet->coverage;
    r.timer.start("wet spectrum");
    const SpectrumResult sp = analyze_spectrum(*wet->height, s.options.threads);
    RoughnessSpectrum homogeneous = wet_spectrum(r.dry_spectrum, sp.psd, sp.nyquist, phi);
    r.timer.start("wet mu(v)");
    r.wet_homogeneous = curve("wet-homogeneous", homogeneous, s, 1.0, 1.0);
    RoughnessSpectrum local = homogeneous;
    local.scale = 1 / phi;
    r.wet_local = curve("wet-local", local, s, phi, phi);
    sealed = local;
  }
  if (s.film) {
    r.timer.start("film at speed");
    // mu_h(v): the local sealing model's friction on a wet surface (the water left in the pools
    // once the film has drained), the dry one otherwise.
    const RoughnessSpectrum& hyst = sealed ? *sealed : r.dry_spectrum;
    const double scale = sealed ? 1 - r.coverage : 1.0;
    auto mu_h = [&](const std::vector<double>& v) {
      if (exact_mu) return exact_mu(v);
      std::vector<double> mu;
      for (const FrictionPoint& p : friction_curve(hyst, s.compound, v, s.options)) mu.push_back(scale * p.mu);
      return mu;
    };
    r.film = skid_curve(r.dry_spectrum, s.compound, s.options, *s.film, s.speeds, mu_h);
    if (s.band) {
      r.timer.start("skid-number band");
      const SkidInputs in{r.dry_spectrum, hyst, scale, s.compound, s.options, *s.film};
      UncertaintySetup setup = *s.band;
      if (setup.ranges.empty()) setup.ranges = default_ranges(in);
      r.band_ranges = setup.ranges;
      r.band = skid_number_band(in, setup);
    }
  }
  r.timer.start("checks");
  r.checks = scene_checks(r, s);
  r.timer.stop();
  return r;
}

std::vector<std::pair<double, double>> mu_against_q1(const FrictionRun& r, const FrictionScene& s, double speed,
                                                     const std::vector<double>& q1s, const std::string& source) {
  std::vector<std::pair<double, double>> out;
  for (double q1 : q1s) {
    const RoughnessSpectrum psd = spectrum_from_psd(r.measured, r.nyquist, r.fit, q1, source);
    out.push_back({q1, hysteresis_friction(psd, s.compound, speed, s.options).mu});
  }
  return out;
}

nlohmann::json friction_curve_json(const FrictionCurve& c) {
  nlohmann::json pts = nlohmann::json::array();
  for (const FrictionPoint& p : c.points)
    pts.push_back({{"v", p.v},
                   {"mu", p.mu},
                   {"area_fraction", p.area_fraction},
                   {"temperature_rise", p.temperature_rise},
                   {"mu_extrapolated", p.mu_extrapolated}});
  return {{"surface", c.surface},
          {"speeds", pts},
          {"peak", {{"mu", c.peak_mu}, {"v", c.peak_v}}},
          {"sn64", c.sn64},
          {"locked_wheel", {{"v", kLockedWheelSpeed}, {"mu", c.at_locked_wheel.mu},
                            {"area_fraction", c.at_locked_wheel.area_fraction},
                            {"temperature_rise", c.at_locked_wheel.temperature_rise}}}};
}

namespace {
nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json film_point_json(const FilmPoint& p) {
  return {{"v", p.v},
          {"mu", p.mu},
          {"mu_hysteresis", p.mu_hysteresis},
          {"mu_viscous", p.mu_viscous},
          {"load_share", p.load_share},
          {"patch_time", p.patch_time},
          {"drain_time", finite_or_null(p.drain_time)},
          {"contact_time", finite_or_null(p.contact_time)},
          {"equilibrium_separation", p.equilibrium_separation},
          {"equilibrium_contact", p.equilibrium_contact},
          {"final_separation", p.final_separation},
          {"trapped", p.trapped}};
}
}  // namespace

nlohmann::json skid_curve_json(const SkidCurve& c, const FilmScene& film, double temperature) {
  nlohmann::json speeds = nlohmann::json::array(), skid = nlohmann::json::array();
  for (const FilmPoint& p : c.points) speeds.push_back(film_point_json(p));
  for (const FilmPoint& p : c.skid) skid.push_back(film_point_json(p));
  nlohmann::json sq = nlohmann::json::array();
  for (const SqueezeState& st : c.squeeze_at_test)
    sq.push_back({{"t", st.t}, {"separation", st.separation}, {"asperity_pressure", st.asperity_pressure}, {"contact", st.contact}});
  return {{"test", film.test.name},
          {"squeeze_at_test", sq},
          {"source", film.test.source},
          {"patch_length", film.test.patch_length},
          {"drainage_length", film.test.drainage_length},
          {"slip_speed", film.test.slip_speed},
          {"water_film", film.test.water_film},
          {"viscosity", water_viscosity(temperature)},
          {"critical_contact", film.critical_contact},
          {"sn", c.sn},
          {"sp_kmh", finite_or_null(c.sp_kmh)},
          {"sp_fit_rms", c.sp_fit_rms},
          {"fr60", c.fr60},
          {"hydroplaning_kmh", finite_or_null(c.hydroplaning_kmh)},
          {"at_test", film_point_json(c.at_test)},
          {"speeds", speeds},
          {"skid", skid}};
}

nlohmann::json skid_band_json(const SkidBand& b, const std::vector<InputRange>& ranges) {
  nlohmann::json rs = nlohmann::json::array(), tornado = nlohmann::json::array();
  for (const InputRange& r : ranges) rs.push_back({{"name", r.name}, {"low", r.low}, {"high", r.high}, {"logarithmic", r.logarithmic}});
  for (const TornadoRow& t : b.tornado)
    tornado.push_back({{"name", t.name}, {"low", t.low}, {"high", t.high}, {"sn_low", t.sn_low}, {"sn_high", t.sn_high}});
  return {{"nominal", b.nominal}, {"p05", b.p05}, {"p95", b.p95}, {"min", b.min}, {"max", b.max},
          {"samples", b.samples.size()}, {"evaluations", b.evaluations}, {"ranges", rs}, {"tornado", tornado}};
}

nlohmann::json hysteresis_validity_json(const std::vector<ValidityCheck>& checks) {
  nlohmann::json list = nlohmann::json::array();
  bool valid = true;
  for (const ValidityCheck& c : checks) {
    list.push_back({{"check", c.name}, {"passed", c.passed}, {"detail", c.detail}, {"decides_model", c.decides_model}});
    if (c.decides_model && !c.passed) valid = false;
  }
  return {{"model", "hysteresis"},
          {"mechanism", "viscoelastic hysteresis of the rubber (Persson 2001), the friction a tyre has"},
          {"valid", valid},
          {"checks", list}};
}

nlohmann::json friction_run_json(const FrictionRun& r, const FrictionScene& s) {
  nlohmann::json j = friction_curve_json(r.dry);
  j["model"] = "hysteresis";
  j["compound"] = compound_to_json(s.compound);
  j["compound"]["path"] = s.compound_path;
  j["temperature"] = s.options.temperature;
  j["pressure"] = s.options.pressure;
  j["q0"] = r.dry_spectrum.q_start;
  j["q1"] = r.dry_spectrum.q_end;
  if (s.mpd) j["mpd"] = r.mpd;
  j["q1_choice"] = r.q1_choice;
  j["q_measured"] = r.dry_spectrum.q_measured;
  j["extrapolated"] = r.dry_spectrum.extrapolated();
  j["extension_beta"] = r.dry_spectrum.extension_beta;
  j["flash_temperature"] = s.options.flash_temperature;
  j["points_per_decade"] = s.options.points_per_decade;
  j["validity"] = hysteresis_validity_json(r.checks);
  j["rung"] = r.model;  // "persson" or "viscoelastic"
  j["rung_chosen_by"] = r.model_reason;
  if (r.exact) {
    const ExactStats& e = *r.exact;
    j["exact"] = {{"grid", {e.nx, e.ny}}, {"refine", e.refine}, {"q_band", e.q_band}, {"max_iterations", e.max_iterations},
                  {"converged", e.converged}, {"message", e.message}, {"max_identity_residual", e.max_identity_residual},
                  {"wall_s", e.wall_s}, {"solves", e.solves}, {"memory_bytes", e.memory_bytes},
                  {"persson_same_band", friction_curve_json(*r.persson_same_band)}};
  }
  if (r.wet_homogeneous) {
    j["wet"] = {{"coverage", r.coverage},
                {"homogeneous", friction_curve_json(*r.wet_homogeneous)},
                {"local", friction_curve_json(*r.wet_local)}};
  }
  if (r.film) j["water_film"] = skid_curve_json(*r.film, *s.film, s.options.temperature);
  if (r.band) j["water_film"]["band"] = skid_band_json(*r.band, r.band_ranges);
  j["timings"] = r.timer.to_json();
  return j;
}

}  // namespace wr
