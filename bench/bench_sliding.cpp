#include "bench/bench_sliding.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "bench/bench_common.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/provenance.hpp"
#include "lib/core/richardson.hpp"
#include "lib/friction/friction_scene.hpp"
#include "lib/friction/hysteresis_friction.hpp"
#include "lib/spectral/viscoelastic_sliding.hpp"
#include "roads/band_limit.hpp"
#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"
#include "roads/synthesize.hpp"

namespace wr::bench {
namespace {

constexpr double kTile = 0.03;  // m, the default scene's tile

HeightMap scene_map(const SlidingBenchSetup& s, std::size_t n, std::uint64_t seed) {
  SynthParams p;
  p.nx = p.ny = n;
  p.dx = kTile / double(n);
  p.h0 = s.h0;
  p.hurst = 0.7;
  p.q0_ratio = 5;
  p.q1 = 2 * std::numbers::pi / kTile * s.band;
  p.seed = seed;
  p.threads = s.threads;
  return synthesize(p).map;
}

Compound bench_compound(const SlidingBenchSetup& s) {
  return read_compound_json(s.compound.empty() ? default_compound_path() : s.compound);
}

std::vector<double> bench_speeds(const SlidingBenchSetup& s) {
  std::vector<double> v;
  const int count = int(std::lround(std::log10(s.speed_max / s.speed_min) * s.per_decade)) + 1;
  for (int i = 0; i < count; ++i) v.push_back(s.speed_min * std::pow(10.0, double(i) / s.per_decade));
  return v;
}

// The map's spectrum on [qL, q1] (no extension).
struct MapSpectrum {
  RadialPsd psd;
  PsdFit fit;
  double nyquist = 0;
  RoughnessSpectrum upto(double q1) const { return spectrum_from_psd(psd, nyquist, fit, q1, "bench map"); }
};

MapSpectrum map_spectrum(const HeightMap& m, int threads) {
  SpectrumResult sp = analyze_spectrum(m, threads);
  MapSpectrum r;
  r.fit = fit_self_affine(sp.psd, sp.nyquist, false);
  r.psd = std::move(sp.psd);
  r.nyquist = sp.nyquist;
  return r;
}

// Octave edges from qL to q1, the first bin from qL to 4 qL (Persson's spectrum needs q1 above
// its second node).
std::vector<double> band_edges(double band) {
  const double ql = 2 * std::numbers::pi / kTile;
  std::vector<double> e = {ql};
  for (double b = 4; b <= band * (1 + 1e-9); b *= 2) e.push_back(b * ql);
  return e;
}

}  // namespace

nlohmann::json sliding_against_persson(const SlidingBenchSetup& s) {
  const Compound compound = bench_compound(s);
  const std::vector<double> speeds = bench_speeds(s);
  const std::vector<double> edges = band_edges(s.band);
  const double q1 = 2 * std::numbers::pi / kTile * s.band;
  nlohmann::json rows = nlohmann::json::array();
  std::size_t memory = 0;
  for (std::uint64_t seed : s.seeds) {
    const HeightMap map = scene_map(s, s.n, seed);
    const MapSpectrum spec = map_spectrum(map, s.threads);
    std::vector<RoughnessSpectrum> cumulative;  // Persson's spectrum up to each edge but the first
    for (std::size_t k = 1; k < edges.size(); ++k) cumulative.push_back(spec.upto(k + 1 == edges.size() ? q1 : edges[k]));
    SlidingOptions so;
    so.tolerance = s.tolerance;
    so.threads = s.threads;
    so.planning = FftPlanning::measure;
    for (double pressure : s.pressures) {
      ViscoelasticSliding solver(map, compound, s.temperature, so);
      memory = solver.memory_bytes();
      FrictionOptions fo;
      fo.pressure = pressure;
      fo.temperature = s.temperature;
      fo.threads = 1;
      for (double v : speeds) {
        const SlidingResult r = solver.solve(v, pressure);
        const FrictionPoint pe = hysteresis_friction(cumulative.back(), compound, v, fo);
        // The exact dissipation by octaves of |q|, and above the band: the rubber's face bends at
        // the contact spots' edges on scales finer than the road's.
        std::vector<double> all_edges = edges;
        all_edges.push_back(1e300);
        const std::vector<double> exact_bins = solver.friction_by_wavenumber(all_edges);
        nlohmann::json bands = nlohmann::json::array();
        double before = 0;
        for (std::size_t k = 0; k + 1 < all_edges.size(); ++k) {
          const bool above = k + 2 == all_edges.size();
          const double upto = above ? before : hysteresis_friction(cumulative[k], compound, v, fo).mu;
          bands.push_back({{"q_low", all_edges[k]}, {"q_high", above ? nullptr : nlohmann::json(all_edges[k + 1])},
                           {"exact", exact_bins[k]}, {"persson", upto - before}});
          before = upto;
        }
        rows.push_back({{"seed", seed}, {"pressure", pressure}, {"v", v}, {"mu", r.mu}, {"mu_dissipation", r.mu_dissipation},
                        {"identity_residual", r.identity_residual}, {"area_fraction", r.area_fraction},
                        {"mu_persson", pe.mu}, {"area_persson", pe.area_fraction}, {"iterations", r.iterations},
                        {"fft_pairs", r.fft_pairs}, {"wall_s", r.wall_s}, {"converged", r.converged},
                        {"message", r.message}, {"bands", bands}});
        std::fprintf(stderr, "  seed %llu  sigma0 %.3g Pa  v %.3g m/s: mu %.4f (Persson %.4f)  A/A0 %.4f (%.4f)  %d its  %.2f s%s\n",
                     static_cast<unsigned long long>(seed), pressure, v, r.mu, pe.mu, r.area_fraction, pe.area_fraction,
                     r.iterations, r.wall_s, r.converged ? "" : "  NOT CONVERGED");
      }
    }
  }
  // Over the seeds: the mean of each model and the ratio of the means.
  std::map<std::pair<double, double>, std::array<double, 6>> acc;  // mu, persson, area, area_p, count, wall
  for (const auto& r : rows) {
    auto& a = acc[{r["pressure"].get<double>(), r["v"].get<double>()}];
    a[0] += r["mu"].get<double>();
    a[1] += r["mu_persson"].get<double>();
    a[2] += r["area_fraction"].get<double>();
    a[3] += r["area_persson"].get<double>();
    a[4] += 1;
    a[5] += r["wall_s"].get<double>();
  }
  nlohmann::json summary = nlohmann::json::array();
  for (const auto& [key, a] : acc)
    summary.push_back({{"pressure", key.first}, {"v", key.second}, {"mu", a[0] / a[4]}, {"mu_persson", a[1] / a[4]},
                       {"ratio", a[1] / a[0]}, {"area_fraction", a[2] / a[4]}, {"area_persson", a[3] / a[4]},
                       {"area_ratio", a[3] / a[2]}, {"wall_s", a[5] / a[4]}});
  return {{"n", s.n}, {"band", s.band}, {"h0", s.h0}, {"temperature", s.temperature}, {"tolerance", s.tolerance},
          {"compound", compound.name}, {"seeds", s.seeds}, {"pressures", s.pressures}, {"rows", rows},
          {"summary", summary}, {"memory_bytes", memory}, {"peak_rss_bytes", double(peak_rss_bytes())}};
}

nlohmann::json sliding_grid_convergence(const SlidingBenchSetup& s, const std::vector<std::size_t>& sizes,
                                        const std::vector<double>& speeds) {
  const Compound compound = bench_compound(s);
  const std::uint64_t seed = s.seeds.empty() ? 1 : s.seeds.front();
  const double pressure = s.pressures.empty() ? 0.3e6 : s.pressures.back();
  nlohmann::json grids = nlohmann::json::array();
  std::vector<std::vector<double>> mu(speeds.size()), area(speeds.size());
  const HeightMap base = scene_map(s, sizes.front(), seed);
  for (std::size_t n : sizes) {
    const HeightMap map = n == base.nx ? base : band_limited(base, 1e300, n / base.nx, s.threads);
    SlidingOptions so;
    so.tolerance = s.tolerance;
    so.threads = s.threads;
    so.planning = FftPlanning::measure;
    ViscoelasticSliding solver(map, compound, s.temperature, so);
    nlohmann::json pts = nlohmann::json::array();
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      const SlidingResult r = solver.solve(speeds[i], pressure);
      mu[i].push_back(r.mu);
      area[i].push_back(r.area_fraction);
      pts.push_back({{"v", speeds[i]}, {"mu", r.mu}, {"mu_dissipation", r.mu_dissipation}, {"area_fraction", r.area_fraction},
                     {"identity_residual", r.identity_residual}, {"iterations", r.iterations}, {"wall_s", r.wall_s},
                     {"converged", r.converged}});
      std::fprintf(stderr, "  %zu^2  v %.3g m/s: mu %.5f  A/A0 %.5f  residual %.2e  %d its  %.1f s\n", n, speeds[i], r.mu,
                   r.area_fraction, r.identity_residual, r.iterations, r.wall_s);
    }
    grids.push_back({{"n", n}, {"points_per_shortest_wavelength", double(n) / s.band}, {"memory_bytes", solver.memory_bytes()},
                     {"points", pts}});
  }
  // Persson's theory on the same map's band at the same speeds (best of 3 timings).
  const MapSpectrum spec = map_spectrum(base, s.threads);
  const RoughnessSpectrum band = spec.upto(2 * std::numbers::pi / kTile * s.band);
  nlohmann::json persson = nlohmann::json::array();
  FrictionOptions fo;
  fo.pressure = pressure;
  fo.temperature = s.temperature;
  fo.threads = 1;
  for (double v : speeds) {
    double best = 1e300, mu_p = 0;
    for (int k = 0; k < 3; ++k) {
      const double t0 = now();
      mu_p = hysteresis_friction(band, compound, v, fo).mu;
      best = std::min(best, now() - t0);
    }
    persson.push_back({{"v", v}, {"mu", mu_p}, {"wall_s", best}});
  }
  nlohmann::json est = nlohmann::json::array();
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    nlohmann::json e = {{"v", speeds[i]}, {"mu", mu[i]}, {"area_fraction", area[i]}};
    const std::size_t m = mu[i].size();
    if (m >= 3) {
      if (auto r = richardson_three(mu[i][m - 3], mu[i][m - 2], mu[i][m - 1])) {
        e["limit"] = r->limit;
        e["order"] = r->order;
        e["gci"] = r->error;
        e["relative_error"] = r->error / std::abs(r->limit);
      } else {
        e["limit"] = nullptr;
        e["note"] = "not in the asymptotic range";
      }
      e["finest_change"] = std::abs(mu[i][m - 1] - mu[i][m - 2]) / std::abs(mu[i][m - 1]);
    }
    est.push_back(e);
  }
  return {{"band", s.band}, {"seed", seed}, {"pressure", pressure}, {"grids", grids}, {"estimates", est}, {"persson", persson},
          {"peak_rss_bytes", double(peak_rss_bytes())}};
}

}  // namespace wr::bench
