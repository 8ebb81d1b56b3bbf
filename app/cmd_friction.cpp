// `wetroad friction SURFACE [--wet WET.h5]`: Persson's hysteresis friction mu(v), dry and wet
// (lib/friction/friction_scene.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/print_summary.hpp"
#include "app/friction_options.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"
#include "lib/friction/friction_file.hpp"
#include "lib/friction/friction_scene.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "reports/plot.hpp"
#include "roads/surface_import.hpp"
#include "water/water_file.hpp"
#include "wetroad/version.hpp"

namespace wr::app {
namespace {

struct FrictionCli {
  std::string input, wet, compound, json, out, plot, plot_q1, plot_squeeze, test = "e274-ribbed";
  double water_film = 0;
  bool no_film = false, band = false;
  std::vector<std::string> band_ranges;
  int band_samples = 32;
  CLI::Option* film_opt = nullptr;
  double temperature = 20, pressure = 3e5;
  std::vector<double> speeds, speed_range;
  std::string q1, model = "auto";
  std::size_t exact_refine = kDefaultExactRefine;
  bool flash = false, quiet = false;
  int points_per_decade = 48, threads = 0;
  CLI::Option *q1_opt = nullptr, *speeds_opt = nullptr, *range_opt = nullptr;
};

std::vector<double> log_speeds(const std::vector<double>& range) {
  const double a = range[0], b = range[1], n = range[2];
  if (!(a > 0 && b > a && std::isfinite(b)))
    throw InputError("--speed-range", "give A B N with 0 < A < B (m/s)");
  if (!(n >= 2 && n <= 1000 && n == std::floor(n))) throw InputError("--speed-range", "N must be a whole number in 2 ... 1000");
  std::vector<double> v;
  for (int i = 0; i < static_cast<int>(n); ++i) v.push_back(a * std::pow(b / a, i / (n - 1)));
  return v;
}

PlotSpec curve_plot(const FrictionRun& r, const FrictionScene& s) {
  PlotSpec p;
  p.title = std::string("hysteresis friction, ") + s.compound.name + (s.compound.synthetic ? " (SYNTHETIC compound)" : "") +
            (s.options.flash_temperature ? ", flash temperature" : ", isothermal");
  p.xlabel = "sliding speed v (m/s)";
  p.ylabel = "mu";
  p.logx = true;
  auto series = [](const FrictionCurve& c, const std::string& label) {
    PlotSeries ps;
    ps.label = label;
    for (const FrictionPoint& q : c.points) {
      ps.x.push_back(q.v);
      ps.y.push_back(q.mu);
    }
    return ps;
  };
  p.series.push_back(series(r.dry, r.exact ? "dry, exact steady sliding on the map" : "dry"));
  if (r.persson_same_band) p.series.push_back(series(*r.persson_same_band, "dry, Persson on the same band"));
  if (r.wet_homogeneous && r.exact) {
    char cov[64];
    std::snprintf(cov, sizeof cov, " (coverage %.0f %%)", 100 * r.coverage);
    p.series.push_back(series(*r.wet_homogeneous, "wet, sealed pools as flat walls, exact" + std::string(cov)));
  } else if (r.wet_homogeneous) {
    char cov[64];
    std::snprintf(cov, sizeof cov, " (coverage %.0f %%)", 100 * r.coverage);
    p.series.push_back(series(*r.wet_homogeneous, "wet, homogeneous sealing" + std::string(cov)));
    p.series.push_back(series(*r.wet_local, "wet, local sealing" + std::string(cov)));
  }
  if (r.film) {
    PlotSeries ps;
    ps.label = "under a " + number_text(1e3 * s.film->test.water_film) + " mm water film (" + s.film->test.name + ")";
    for (const FilmPoint& q : r.film->points) {
      ps.x.push_back(q.v);
      ps.y.push_back(q.mu);
    }
    p.series.push_back(ps);
  }
  return p;
}

// u(t) and the asperities' load share at the test's speed, with the time under the tyre marked.
PlotSpec squeeze_plot(const SkidCurve& c, const FilmScene& f, double pressure) {
  PlotSpec p;
  char kmh[32];
  std::snprintf(kmh, sizeof kmh, "%.0f", 3.6 * f.test.slip_speed);
  p.title = "squeeze-out of a " + number_text(1e3 * f.test.water_film) + " mm film at " + kmh + " km/h (" + f.test.name +
            "); vertical line: time under the tyre";
  p.xlabel = "time after the element enters the patch t (s)";
  p.ylabel = "mean separation (mm), load share";
  p.logx = true;
  PlotSeries u{"mean separation u (mm)", {}, {}, "lines", {}}, share{"asperities' load share p_c / sigma0", {}, {}, "lines", {}};
  double umax = 0;
  for (const SqueezeState& st : c.squeeze_at_test) {
    if (st.t <= 0) continue;
    u.x.push_back(st.t);
    u.y.push_back(1e3 * st.separation);
    share.x.push_back(st.t);
    share.y.push_back(st.asperity_pressure / pressure);
    umax = std::max(umax, 1e3 * st.separation);
  }
  PlotSeries patch{"time under the tyre Lc / v", {c.at_test.patch_time, c.at_test.patch_time}, {0.0, std::max(1.0, umax)}, "lines", {}};
  p.series = {u, share, patch};
  return p;
}

void print_film(const SkidCurve& c, const FilmScene& f) {
  std::printf("\nwet friction at speed: test %s, water film %.3g mm, patch %.3g m, drainage length %.3g m\n", f.test.name.c_str(),
              1e3 * f.test.water_film, f.test.patch_length, f.test.drainage_length);
  std::printf("  %9s %7s %8s %10s %10s %11s %11s\n", "v (km/h)", "SN", "mu_h", "load share", "mu viscous", "drain (ms)", "patch (ms)");
  for (const FilmPoint& p : c.skid)
    std::printf("  %9.0f %7.1f %8.4f %10.3f %10.2e %11.3g %11.3g\n", 3.6 * p.v, 100 * p.mu, p.mu_hysteresis, p.load_share,
                p.mu_viscous, 1e3 * p.drain_time, 1e3 * p.patch_time);
  std::printf("  skid number at %.0f km/h: SN %.1f (hysteresis of the drained road alone: %.1f)\n", 3.6 * f.test.slip_speed, c.sn,
              100 * c.at_test.mu_hysteresis);
  if (std::isfinite(c.sp_kmh))
    std::printf("  speed constant Sp %.1f km/h (ASTM E1960 exponential fitted over 20-100 km/h, rms of ln mu %.3f)\n", c.sp_kmh,
                c.sp_fit_rms);
  else
    std::printf("  speed constant Sp: none (mu does not fall with speed over 20-100 km/h)\n");
  std::printf("  FR60 (mu at 60 km/h) %.4f\n", c.fr60);
  if (std::isfinite(c.hydroplaning_kmh))
    std::printf("  hydroplaning above %.0f km/h (the film does not reach the asperities within the patch)\n", c.hydroplaning_kmh);
  else
    std::printf("  no hydroplaning: the texture holds the film or drains it to the asperities at any speed\n");
}

// NAME=LOW:HIGH (the input's own unit) for --band-range; names as lib/friction/uncertainty.hpp.
InputRange parse_band_range(const std::string& text) {
  const auto eq = text.find('='), colon = text.find(':', eq == std::string::npos ? 0 : eq);
  const std::string name = text.substr(0, eq);
  static const std::vector<std::string> names = {"pressure", "temperature", "water_film", "q1", "compound_shift"};
  if (eq == std::string::npos || colon == std::string::npos || std::find(names.begin(), names.end(), name) == names.end())
    throw InputError("--band-range", "\"" + text + "\": write NAME=LOW:HIGH with NAME one of pressure (Pa), temperature (C), "
                                     "water_film (m), q1 (1/m), compound_shift (decades)");
  double lo = 0, hi = 0;
  try {
    lo = std::stod(text.substr(eq + 1, colon - eq - 1));
    hi = std::stod(text.substr(colon + 1));
  } catch (const std::exception&) {
    throw InputError("--band-range", "\"" + text + "\": LOW and HIGH must be numbers");
  }
  const bool positive = name != "temperature" && name != "compound_shift";
  if (!(lo < hi && std::isfinite(lo) && std::isfinite(hi)) || (positive && !(lo > 0)))
    throw InputError("--band-range", "\"" + text + "\": needs LOW < HIGH" + std::string(positive ? ", both > 0" : ""));
  if (name == "water_film") check_water_film(hi, "--band-range");
  return {name, lo, hi, name == "q1" || name == "water_film"};
}

void print_band(const SkidBand& b, const std::vector<InputRange>& ranges) {
  std::printf("  skid number's band over the inputs' ranges: 5-95 %% %.1f ... %.1f, extremes %.1f ... %.1f "
              "(Latin hypercube, %zu samples; %d evaluations)\n", b.p05, b.p95, b.min, b.max, b.samples.size(), b.evaluations);
  std::printf("  %-16s %12s %12s %9s %9s\n", "input", "low", "high", "SN low", "SN high");
  for (const TornadoRow& t : b.tornado) std::printf("  %-16s %12.4g %12.4g %9.1f %9.1f\n", t.name.c_str(), t.low, t.high, t.sn_low, t.sn_high);
  (void)ranges;
}

// The exact rung's curve beside Persson's theory on the same band.
void print_exact(const FrictionRun& r) {
  const ExactStats& e = *r.exact;
  std::printf("  exact rung: %zux%zu grid (the map's band q <= %.4g 1/m, refined x%zu), %d solves, %.1f s, at most %d iterations, "
              "arrays %.0f MiB\n", e.nx, e.ny, e.q_band, e.refine, e.solves, e.wall_s, e.max_iterations, e.memory_bytes / 1048576.0);
  std::printf("\n  %11s %8s %10s %10s %8s %10s", "v (m/s)", "mu", "A/A0", "Persson mu", "ratio", "Persson A");
  if (r.wet_homogeneous) std::printf(" %14s", "mu wet, sealed");
  std::printf("\n");
  for (std::size_t i = 0; i < r.dry.points.size(); ++i) {
    const FrictionPoint &p = r.dry.points[i], &q = r.persson_same_band->points[i];
    std::printf("  %11.4g %8.4f %10.4g %10.4f %8.3f %10.4g", p.v, p.mu, p.area_fraction, q.mu, p.mu > 0 ? q.mu / p.mu : 0.0,
                q.area_fraction);
    if (r.wet_homogeneous) std::printf(" %14.4f", r.wet_homogeneous->points[i].mu);
    std::printf("\n");
  }
}

void print_run(const FrictionRun& r, const FrictionScene& s, const std::vector<std::pair<double, double>>& q1_scan) {
  std::printf("hysteresis friction (%s), compound: %s%s\n",
              r.exact ? "exact steady viscoelastic sliding on the map" : "Persson", s.compound.name.c_str(),
              s.compound.synthetic ? "  [SYNTHETIC]" : "");
  std::printf("  model: %s (%s)\n", r.model.c_str(), r.model_reason.c_str());
  std::printf("  sigma0 %.3g Pa, T0 %.1f C, flash temperature %s\n", s.options.pressure, s.options.temperature,
              s.options.flash_temperature ? "on" : "off");
  std::printf("  cut-off q1 %.4g 1/m (%s)\n", r.dry_spectrum.q_end,
              r.q1_choice == "default" ? "default: 2 pi / 20 um or the map's last resolved wavenumber"
              : r.q1_choice == "given"           ? "given"
              : r.q1_choice == "the map's band"  ? "the map's band: the exact rung sees no more"
                                                 : (r.q1_choice + " criterion: the extrapolated spectrum's rms slope reaches it").c_str());
  std::printf("  spectrum q %.3g ... %.3g 1/m, measured to %.3g 1/m%s\n", r.dry_spectrum.q_start, r.dry_spectrum.q_end,
              r.dry_spectrum.q_measured,
              r.dry_spectrum.extrapolated() ? "; above that EXTRAPOLATED along the fitted self-affine law" : "");
  if (r.exact) {
    print_exact(r);
  } else {
    std::printf("\n  %11s %8s %10s %8s", "v (m/s)", "mu", "A/A0", "dT (K)");
    if (r.wet_homogeneous) std::printf(" %10s %10s", "mu wet-hom", "mu wet-loc");
    std::printf("\n");
    for (std::size_t i = 0; i < r.dry.points.size(); ++i) {
      const FrictionPoint& p = r.dry.points[i];
      std::printf("  %11.4g %8.4f %10.4g %8.2f", p.v, p.mu, p.area_fraction, p.temperature_rise);
      if (r.wet_homogeneous) std::printf(" %10.4f %10.4f", r.wet_homogeneous->points[i].mu, r.wet_local->points[i].mu);
      std::printf("\n");
    }
  }
  std::printf("\n  peak: mu %.4f at v %.3g m/s\n", r.dry.peak_mu, r.dry.peak_v);
  std::printf("  at 64 km/h, drained road: mu %.4f", r.dry.at_locked_wheel.mu);
  if (r.wet_homogeneous && r.exact)
    std::printf("; wet (coverage %.1f %%), sealed pools as flat walls: %.4f", 100 * r.coverage, r.wet_homogeneous->at_locked_wheel.mu);
  else if (r.wet_homogeneous)
    std::printf("; wet (coverage %.1f %%): homogeneous %.4f, local %.4f", 100 * r.coverage, r.wet_homogeneous->at_locked_wheel.mu,
                r.wet_local->at_locked_wheel.mu);
  std::printf("\n");
  if (!q1_scan.empty()) {
    std::printf("  dry mu at 17.9 m/s against the cut-off q1 (the unmeasured scales):");
    for (const auto& [q1, mu] : q1_scan) std::printf(" %.3g:%.3f", q1, mu);
    std::printf("\n");
  }
  if (r.film) print_film(*r.film, *s.film);
  if (r.band) print_band(*r.band, r.band_ranges);
  std::printf("\nchecks\n");
  for (const ValidityCheck& c : r.checks)
    std::printf("  [%s] %s: %s\n", c.passed ? "pass" : (c.decides_model ? "FAIL" : "flag"), c.name.c_str(), c.detail.c_str());
  std::printf("\ntimings\n%s", r.timer.table().c_str());
}

int run_friction_command(const FrictionCli& c) {
  OutputSet outputs;
  outputs.input(c.input);
  outputs.input(c.wet);
  outputs.input(c.compound);
  const std::string json_path = outputs.add("--json", c.json), out_path = outputs.add("--out", c.out),
                    plot_path = outputs.add("--plot", c.plot), plot_q1_path = outputs.add("--plot-q1", c.plot_q1),
                    plot_squeeze_path = outputs.add("--plot-squeeze", c.plot_squeeze);
  if (!plot_squeeze_path.empty() && c.no_film) throw InputError("--plot-squeeze", "charts the film's squeeze-out: not with --no-film");
  FrictionScene s;
  s.compound_path = c.compound.empty() ? default_compound_path() : c.compound;
  s.compound = read_compound_json(s.compound_path);
  s.options.pressure = c.pressure;
  s.options.temperature = c.temperature;
  s.options.flash_temperature = c.flash;
  s.options.points_per_decade = c.points_per_decade;
  s.options.threads = c.threads;
  s.model = parse_hysteresis_model(c.model, "--model");
  s.exact_refine = c.exact_refine;
  s.progress = !c.quiet;
  if (c.q1_opt->count()) apply_q1_option(c.q1, "--q1", s);
  if (c.speeds_opt->count() && c.range_opt->count()) throw InputError("--speeds", "give --speeds or --speed-range, not both");
  s.speeds = c.speeds_opt->count() ? c.speeds : log_speeds(c.range_opt->count() ? c.speed_range : std::vector<double>{1e-6, 100, 33});
  apply_film_options(c.no_film, *c.film_opt, c.water_film, c.test, s);
  if (c.band || !c.band_ranges.empty()) {
    if (!s.film) throw InputError("--band", "the band is the skid number's: not with --no-film");
    if (!(c.band_samples >= 4 && c.band_samples <= 10000)) throw InputError("--band-samples", "must lie in 4 ... 10000");
    UncertaintySetup u;
    u.samples = c.band_samples;
    for (const std::string& t : c.band_ranges) u.ranges.push_back(parse_band_range(t));
    s.band = u;
  }
  check_friction_scene(s);

  const LoadedSurface dry = load_surface(c.input);
  print_load_warnings(dry);
  if (!c.quiet) print_import(dry);
  std::optional<LoadedSurface> wet_map;
  std::optional<WetSurface> wet;
  if (!c.wet.empty()) {
    const double coverage = check_wet_file(c.wet, c.input);
    wet_map = load_surface(c.wet);
    wet = WetSurface{&wet_map->map, coverage};
  }
  const FrictionRun r = run_friction(dry.map, wet, s, c.input);
  std::vector<std::pair<double, double>> q1_scan;
  if (r.dry_spectrum.q_measured > 0 && !r.exact) {
    std::vector<double> q1s;
    for (int k = 0; k <= 8; ++k) q1s.push_back(r.dry_spectrum.q_measured * std::pow(10.0, k / 4.0));
    q1_scan = mu_against_q1(r, s, kLockedWheelSpeed, q1s, c.input);
  }

  Provenance prov;
  prov.command = "friction";
  prov.inputs = {{"surface", c.input}, {"wet", c.wet}, {"compound", s.compound_path}};
  prov.parameters = {{"pressure", s.options.pressure},       {"temperature", s.options.temperature},
                     {"flash_temperature", c.flash},         {"q1", r.dry_spectrum.q_end},
                     {"points_per_decade", c.points_per_decade}, {"speeds", s.speeds}};
  if (s.film) {
    prov.parameters["test"] = s.film->test.name;
    prov.parameters["water_film"] = s.film->test.water_film;
  }
  prov.parameters["model"] = c.model;
  prov.parameters["exact_refine"] = c.exact_refine;
  prov.model = (r.exact ? std::string("hysteresis by exact steady viscoelastic sliding on the map (FFT boundary elements); "
                                      "Persson 2001 on the same band beside it")
                        : std::string("hysteresis (Persson 2001; sealing: homogeneous and local)")) +
               (s.film ? "; water film squeezed out at speed (Lorenz & Persson 2010; effective-medium flow)" : "");
  prov.timings = r.timer.to_json();
  nlohmann::json j = friction_run_json(r, s);
  nlohmann::json scan = nlohmann::json::array();
  for (const auto& [q1, mu] : q1_scan) scan.push_back({{"q1", q1}, {"mu_locked_wheel", mu}});
  j["q1_scan"] = scan;
  j["provenance"] = prov.to_json();
  if (!json_path.empty()) write_text_atomically(json_path, j.dump(2) + "\n");
  if (!out_path.empty()) write_friction_file(out_path, r, j, prov.to_json());
  if (!plot_path.empty()) write_svg_plot(plot_path, curve_plot(r, s));
  if (!plot_q1_path.empty()) {
    PlotSpec p;
    p.title = "mu at 17.9 m/s against the cut-off q1 (measured to " + std::to_string(static_cast<int>(r.dry_spectrum.q_measured)) +
              " 1/m; " + (s.options.flash_temperature ? "flash temperature)" : "isothermal)");
    p.xlabel = "q1 (1/m)";
    p.ylabel = "mu";
    p.logx = true;
    PlotSeries ps;
    ps.label = "dry";
    for (const auto& [q1, mu] : q1_scan) {
      ps.x.push_back(q1);
      ps.y.push_back(mu);
    }
    p.series.push_back(ps);
    write_svg_plot(plot_q1_path, p);
  }
  if (!plot_squeeze_path.empty()) write_svg_plot(plot_squeeze_path, squeeze_plot(*r.film, *s.film, s.options.pressure));
  outputs.commit();
  if (!c.quiet) print_run(r, s, q1_scan);
  return 0;
}

}  // namespace

Command add_friction(CLI::App& root) {
  auto c = std::make_shared<FrictionCli>();
  CLI::App* s = root.add_subcommand("friction", "hysteresis friction mu(v) of tread rubber on a dry and a wet surface");
  s->footer(
      "Persson's theory of rubber friction (J. Chem. Phys. 115, 3840 (2001); the thesis's eq. 3.170):\n"
      "the road's asperities excite the rubber at frequencies q v and its loss modulus dissipates\n"
      "energy. Input: the surface's isotropic PSD (from the map), extended above the measured band\n"
      "to --q1 along the fitted self-affine law (flagged as extrapolated), and the compound's master\n"
      "curve E(omega, T) (WLF shift). --wet adds the wet surface of `wetroad fill` with two sealing\n"
      "models: homogeneous (the wet surface's PSD) and local (sealed water carries load, dissipates\n"
      "nothing; the dry patches keep their roughness). Prints mu(v), A/A0, the flash temperature's\n"
      "rise, the peak and the model's validity checks.\n"
      "Wet at speed (unless --no-film): a water film (--water-film, default E274's 0.5 mm) is squeezed out\n"
      "through the texture while a road element is under the tread (Lorenz & Persson 2010; the test's patch\n"
      "and drainage length, --test); the asperities' load share slides with the hysteresis friction, the\n"
      "water's shears as a film. Prints SN at 20-100 km/h, the skid number at the test's speed, the speed\n"
      "constant Sp (ASTM E1960), FR60 and the hydroplaning speed.\n"
      "--model viscoelastic solves the rubber's steady sliding over the map itself (the exact rung: no mean-field\n"
      "approximation, docs/validation.md) on the map's own band and prints Persson's theory on the same band beside it;\n"
      "with --wet it slides over the sealed surface (pools as flat walls): one exact answer for both sealing models.\n"
      "Default compound: share/compounds/synthetic-tread.json (SYNTHETIC: see its source field).\n"
      "Example: wetroad friction road.h5 --wet road-wet.h5 --flash-temperature --plot mu.svg\n"
      "Example: wetroad friction road.h5 --model viscoelastic --no-film --speed-range 1e-4 10 6");
  s->add_option("surface", c->input, "the dry surface (HDF5 map or text grid)")->type_name("FILE")->required();
  s->add_option("--wet", c->wet, "the wet surface: output of `wetroad fill` (/height, /water_depth)")->type_name("FILE");
  s->add_option("--compound", c->compound, "compound JSON file (default share/compounds/synthetic-tread.json; format: docs/friction-model.md)")->type_name("FILE");
  s->add_option("--temperature", c->temperature, "road and rubber temperature in deg C")->capture_default_str();
  s->add_option("--pressure", c->pressure, "nominal contact pressure sigma0 in Pa")->capture_default_str();
  c->speeds_opt = s->add_option("--speeds", c->speeds, "sliding speeds in m/s");
  c->range_opt = s->add_option("--speed-range", c->speed_range, "A B N: N speeds log-spaced from A to B m/s (default 1e-6 100 33)")
                     ->expected(3);
  c->q1_opt = s->add_option("--q1", c->q1,
                            "short-wavelength cut-off: a wavenumber in 1/m (default 2 pi / 20 um = 3.14e5, or the map's last "
                            "resolved wavenumber if larger), or rms-slope[:S]: where the extrapolated spectrum's rms slope "
                            "reaches S (default 1.3, Lorenz et al. 2015)")
                  ->type_name("Q1");
  s->add_option("--model", c->model,
                "persson: Persson's theory (milliseconds; extrapolates the spectrum to --q1); viscoelastic: exact steady "
                "sliding of the rubber over the map itself (seconds per speed; the map's own band, isothermal, dry), "
                "Persson's theory on the same band beside it; auto: Persson unless its model-deciding check fails on a "
                "map whose band carries the friction")
      ->capture_default_str();
  s->add_option("--exact-refine", c->exact_refine,
                "the exact rung's grid: the map Fourier-interpolated this many times finer (4: mu within about 2 % of "
                "the grid-converged value)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  s->add_flag("--flash-temperature", c->flash, "heat the rubber at each scale by the power the coarser scales dissipate");
  s->add_option("--points-per-decade", c->points_per_decade, "q quadrature nodes per decade")->capture_default_str();
  s->add_option("--json", c->json, "write the result as JSON (SI units)")->type_name("OUTPUT");
  s->add_option("--out", c->out, "write the curves and the spectrum as HDF5")->type_name("OUTPUT");
  s->add_option("--plot", c->plot, "chart mu(v) dry and wet as SVG")->type_name("OUTPUT");
  s->add_option("--plot-q1", c->plot_q1, "chart mu at 17.9 m/s against the cut-off q1 as SVG")->type_name("OUTPUT");
  c->film_opt = s->add_option("--water-film", c->water_film,
                               "depth of the water film ahead of the tyre in m (volume per unit area; default: the test's, 0.5e-3 for E274)");
  s->add_option("--test", c->test,
                "skid test and tyre: e274-ribbed (ASTM E501 rib tyre), e274-smooth (ASTM E524), or a JSON file "
                "(keys: docs/file-formats.md)")
      ->type_name("FILE")
      ->capture_default_str();
  s->add_option("--plot-squeeze", c->plot_squeeze, "chart the film's mean separation and load share against time at the test's speed as SVG")
      ->type_name("OUTPUT");
  s->add_flag("--no-film", c->no_film, "no water film: only the hysteresis friction of the drained road");
  s->add_flag("--band", c->band,
              "the skid number's band and tornado over the inputs' ranges (sigma0 x2/3...x4/3, T +-10 K, film x1/2...x2, "
              "q1 x1/3...x3, a synthetic compound's master curve +-0.5 decades; docs/friction-model.md)");
  s->add_option("--band-range", c->band_ranges,
                "NAME=LOW:HIGH replacing the default ranges (pressure Pa, temperature C, water_film m, q1 1/m, "
                "compound_shift decades); implies --band");
  s->add_option("--band-samples", c->band_samples, "Latin-hypercube samples of the band")->capture_default_str();
  s->add_option("--threads", c->threads, "worker threads over speeds (default: all)")->check(CLI::NonNegativeNumber);
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_friction_command(*c); }};
}

}  // namespace wr::app
