#include "bench/bench_friction.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "lib/friction/friction_scene.hpp"
#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"
#include "roads/synthesize.hpp"

namespace wr::bench {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

template <class F>
double best_of(int repeats, F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) {
    const double t0 = now();
    f();
    best = std::min(best, now() - t0);
  }
  return best;
}

}  // namespace

nlohmann::json friction_speed(std::size_t n, int speeds, int repeats, int threads) {
  SynthParams p;
  p.nx = p.ny = n;
  p.dx = 0.03 / static_cast<double>(n);  // the default scene's 30 mm tile, sampled finer
  p.threads = threads;
  const HeightMap map = synthesize(p).map;
  SpectrumResult sp;
  PsdFit fit;
  const double t_psd = best_of(repeats, [&] {
    sp = analyze_spectrum(map, threads);
    fit = fit_self_affine(sp.psd, sp.nyquist, false);
  });
  const RoughnessSpectrum psd = spectrum_from_psd(sp.psd, sp.nyquist, fit, std::nullopt, "bench surface");
  FrictionScene s;
  s.compound = read_compound_json(default_compound_path());
  s.options.threads = threads;
  for (int i = 0; i < speeds; ++i) s.speeds.push_back(1e-6 * std::pow(1e8, i / double(std::max(1, speeds - 1))));
  std::vector<FrictionPoint> iso, hot;
  const double t_iso = best_of(repeats, [&] { iso = friction_curve(psd, s.compound, s.speeds, s.options); });
  FrictionOptions flash = s.options;
  flash.flash_temperature = true;
  const double t_flash = best_of(repeats, [&] { hot = friction_curve(psd, s.compound, s.speeds, flash); });
  // Wet at speed: the film's squeeze-out and patch average at the same speeds (after mu_h, which
  // is the flash curve above), the skid speeds, Sp and the hydroplaning speed (issue 55, bar 6).
  FilmScene film;
  film.test = tyre_test("e274-ribbed");
  SkidCurve skid;
  const double t_film = best_of(repeats, [&] {
    skid = skid_curve(psd, s.compound, flash, film, s.speeds, [&](const std::vector<double>& v) {
      std::vector<double> mu;
      for (const FrictionPoint& p : friction_curve(psd, s.compound, v, flash)) mu.push_back(p.mu);
      return mu;
    });
  });
  // Speed against accuracy: the largest relative error of mu over the speeds, per node density.
  FrictionOptions ref_opt = s.options;
  ref_opt.points_per_decade = 400;
  const std::vector<FrictionPoint> ref = friction_curve(psd, s.compound, s.speeds, ref_opt);
  nlohmann::json ladder = nlohmann::json::array();
  for (int ppd : {6, 8, 12, 16, 24, 32, 48, 64, 96}) {
    FrictionOptions o = s.options;
    o.points_per_decade = ppd;
    std::vector<FrictionPoint> pts;
    const double t = best_of(repeats, [&] { pts = friction_curve(psd, s.compound, s.speeds, o); });
    double err = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) err = std::max(err, std::abs(pts[i].mu / ref[i].mu - 1));
    ladder.push_back({{"points_per_decade", ppd}, {"seconds", t}, {"max_relative_error", err}});
  }
  double peak_iso = 0, peak_hot = 0;
  for (std::size_t i = 0; i < iso.size(); ++i) {
    peak_iso = std::max(peak_iso, iso[i].mu);
    peak_hot = std::max(peak_hot, hot[i].mu);
  }
  return {{"n", n},
          {"speeds", speeds},
          {"threads", threads},
          {"q_start", psd.q_start},
          {"q_measured", psd.q_measured},
          {"q1", psd.q_end},
          {"psd_seconds", t_psd},
          {"curve_seconds", t_iso},
          {"curve_flash_seconds", t_flash},
          {"peak_mu_isothermal", peak_iso},
          {"peak_mu_flash", peak_hot},
          {"film_seconds", t_film},
          {"film_sn", skid.sn},
          {"film_sp_kmh", std::isfinite(skid.sp_kmh) ? nlohmann::json(skid.sp_kmh) : nlohmann::json(nullptr)},
          {"accuracy_ladder", ladder}};
}

}  // namespace wr::bench
