// Benchmarks of the spectral contact model: speed, shear, kappa (bench/bench_harness.hpp).
#include "bench/bench_harness.hpp"
#include "bench/bench_common.hpp"

#include "lib/fem/amg_hierarchy.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "lib/analytic/contact_theory.hpp"
#include "lib/analytic/hertz.hpp"
#include "lib/analytic/nayak_summits.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/core/provenance.hpp"
#include "lib/core/richardson.hpp"
#include "lib/scene/contact_scene.hpp"
#include "lib/contact/contact_step.hpp"
#include "lib/contact/friction_convergence.hpp"
#include "lib/core/fft.hpp"
#include "lib/contact/periodic_obstacle.hpp"
#include "lib/fem/block_press_shear.hpp"
#include "lib/fem/elastic_block.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "lib/spectral/spectral_press_shear.hpp"
#include "roads/height_stats.hpp"
#include "reports/plot.hpp"
#include "roads/analyze.hpp"
#include "roads/surface_file.hpp"
#include "roads/surface_import.hpp"
#include "roads/synthesize.hpp"
#include "water/depression_hierarchy.hpp"
#include "water/drained_limit.hpp"
#include "water/fill_spill_merge.hpp"
#include "water/rain_fill.hpp"

namespace wr::bench {
namespace {

// The self-affine test surface of the spectral benchmarks: H = 0.7, q0 = 5 qL, q1 = the
// Nyquist wavenumber of a `band_n` grid over the same period, sampled on n x n points.
// Band-limited below every grid's Nyquist wavenumber, so the maps of one seed on different
// grids sample one and the same continuous surface.
HeightMap band_limited_surface(std::size_t n, std::size_t band_n, std::uint64_t seed, int threads,
                               double period = 1e-2) {
  SynthParams p;
  p.nx = p.ny = n;
  p.dx = period / double(n);
  p.h0 = 1e-5;
  p.hurst = 0.7;
  p.q0_ratio = 5;
  p.q1 = std::numbers::pi * double(band_n) / period;
  p.seed = seed;
  p.threads = threads;
  return synthesize(p).map;
}

// Half-spectrum wavenumber ring of a lattice (for the prescribed-slope check).
double rms_slope_spectral(const HeightMap& m, int threads) {
  RealFft2d fft(m.nx, m.ny, threads);
  std::copy(m.h.begin(), m.h.end(), fft.real());
  fft.forward();
  const double qx0 = 2 * std::numbers::pi / m.lx(), qy0 = 2 * std::numbers::pi / m.ly(), n = double(m.size());
  double s = 0;
  for (std::size_t j = 0; j < m.ny; ++j) {
    const double ky = qy0 * (j <= m.ny / 2 ? double(j) : double(j) - double(m.ny));
    for (std::size_t i = 0; i < fft.nxh(); ++i) {
      const double kx = qx0 * double(i), w = (i == 0 || 2 * i == m.nx) ? 1.0 : 2.0;
      s += w * (kx * kx + ky * ky) * std::norm(fft.spectrum()[j * fft.nxh() + i]) / (n * n);
    }
  }
  return std::sqrt(s);
}

// The floor of the spectral benches: one forward + backward transform of an n x n grid with
// the plans the solver uses (measured here when the machine's wisdom file lacks them).
struct FftFloor {
  double planning_s = 0, pair_s = 0;
};
FftFloor fft_pair_floor(std::size_t n, int threads) {
  FftFloor f;
  double t0 = now();
  RealFft2d fft(n, n, threads, nullptr, FftPlanning::measure);
  f.planning_s = now() - t0;
  std::fill(fft.real(), fft.real() + n * n, 1.0);
  const int reps = 10;
  t0 = now();
  for (int r = 0; r < reps; ++r) {
    fft.forward();
    fft.backward();
  }
  f.pair_s = (now() - t0) / reps;
  return f;
}

}  // namespace

nlohmann::json spectral_speed(const std::vector<std::size_t>& sizes, int loads, int threads, double tolerance,
                              int admit_every) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t n : sizes) {
    const HeightMap m = band_limited_surface(n, n, 7, threads);
    const ElasticBody body{1.0, 0.45};
    const double slope = rms_slope_spectral(m, threads);
    const FftFloor floor = fft_pair_floor(n, threads);
    double t0 = now();
    SpectralNormalContact solver(m, body, threads);
    const double setup = now() - t0;
    SpectralOptions opt;
    opt.threads = threads;
    opt.tolerance = tolerance;
    opt.admit_every = admit_every;
    nlohmann::json steps = nlohmann::json::array();
    int iterations = 0, fft_pairs = 0;
    bool all_converged = true;
    t0 = now();
    for (int k = 1; k <= loads; ++k) {
      const double sigma_star = 0.01 * k;  // A/A0 from about 2 % to 20 %
      const SpectralNormalResult r = solver.solve_load(sigma_star * body.e_star() * slope, opt);
      iterations += r.iterations;
      fft_pairs += r.fft_pairs;
      all_converged &= r.converged;
      steps.push_back({{"sigma_star", sigma_star}, {"area_fraction", r.area_fraction}, {"iterations", r.iterations},
                       {"wall_s", r.wall_s}});
      std::fprintf(stderr, "\r  %zu^2: load %d/%d", n, k, loads);
    }
    const double total = now() - t0;
    std::fprintf(stderr, "\n");
    rows.push_back({{"n", n},
                    {"loads", loads},
                    {"threads", threads > 0 ? threads : hardware_threads()},
                    {"rms_slope", slope},
                    {"planning_s", floor.planning_s},
                    {"setup_s", setup},
                    {"solve_s", total},
                    {"iterations", iterations},
                    {"fft_pairs", fft_pairs},
                    {"tolerance", tolerance},
                    {"cg_precision", opt.single_precision_cg() ? "single" : "double"},
                    {"admit_every", admit_every},
                    {"fft_pair_s", floor.pair_s},
                    {"s_per_iteration", total / std::max(iterations, 1)},
                    {"converged", all_converged},
                    {"steps", steps}});
  }
  return rows;
}

nlohmann::json spectral_shear(std::size_t n, double uz, double ux, int steps, int threads, double tolerance) {
  const HeightMap m = band_limited_surface(n, n, 7, threads);
  SpectralTestOptions opt;
  opt.uz = uz;
  opt.ux = ux;
  opt.steps = opt.shear_steps = steps;
  opt.shear = true;
  opt.body = ElasticBody{1.0, 0.45, m.lx()};  // the layer as thick as the period: a cube's height
  opt.solver.threads = threads;
  opt.solver.tolerance = tolerance;
  opt.rms_slope = rms_slope_spectral(m, threads);
  const FftFloor floor = fft_pair_floor(n, threads);
  int done = 0;
  const SpectralTestResult r = run_spectral_contact_test(m, opt, [&](const ContactStep&) {
    std::fprintf(stderr, "\r  %zu^2 shear test: step %d/%d", n, ++done, 2 * steps);
  });
  std::fprintf(stderr, "\n");
  int geometry = 0, cg = 0;
  nlohmann::json rows = nlohmann::json::array();
  for (const ContactStep& s : r.steps) {
    geometry += s.signorini_iterations;
    cg += s.linear_iterations;
    rows.push_back({{"uz", s.uz}, {"ux", s.ux}, {"mu", s.mu}, {"area_fraction", s.area_fraction},
                    {"sigma_star", s.sigma_star}, {"geometry_iterations", s.signorini_iterations},
                    {"cg_iterations", s.linear_iterations}, {"converged", s.converged}, {"wall_s", s.wall_s}});
  }
  return {{"n", n},
          {"threads", threads > 0 ? threads : hardware_threads()},
          {"thickness", opt.body.thickness},
          {"rms_slope", opt.rms_slope},
          {"uz", uz},
          {"ux", ux},
          {"steps_per_phase", steps},
          {"tolerance", tolerance},
          {"cg_precision", opt.solver.single_precision_cg() ? "single" : "double"},
          {"geometry_tolerance", opt.geometry_tolerance},
          {"planning_s", floor.planning_s},
          {"fft_pair_s", floor.pair_s},
          {"setup_s", r.wall_setup},
          {"wall_s", r.wall_s},
          {"geometry_iterations", geometry},
          {"cg_iterations", cg},
          {"converged", !r.failed},
          {"steps", rows}};
}

nlohmann::json spectral_kappa(const std::vector<std::size_t>& sizes, std::size_t band_n, int seeds, int threads,
                              bool period_effect) {
  const ElasticBody body{1.0, 0.45};
  const std::vector<double> sigmas = {0.005, 0.01, 0.02, 0.05, 0.1, 0.2};
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t n : sizes) {
    std::vector<double> area(sigmas.size(), 0.0);
    double kappa = 0, slope_mean = 0, wall = 0;
    for (int s = 0; s < seeds; ++s) {
      // Grid effect: one period (1 cm), the band of a band_n grid, finer samplings. Period effect:
      // the spacing of the first size kept, the period growing with n, q1 at each grid's Nyquist.
      const double period = period_effect ? 1e-2 * double(n) / double(sizes.front()) : 1e-2;
      const HeightMap m = band_limited_surface(n, period_effect ? n : band_n, 100 + std::uint64_t(s), threads, period);
      // sigma* uses the slope of the continuous band-limited surface (the same on every grid).
      const double slope = rms_slope_spectral(m, threads);
      slope_mean += slope / seeds;
      SpectralNormalContact solver(m, body, threads);
      SpectralOptions opt;
      opt.threads = threads;
      opt.tolerance = 1e-10;
      const double t0 = now();
      for (std::size_t k = 0; k < sigmas.size(); ++k) {
        const SpectralNormalResult r = solver.solve_load(sigmas[k] * body.e_star() * slope, opt);
        area[k] += r.area_fraction / seeds;
        if (k == 0) kappa += r.area_fraction / sigmas[k] / seeds;
      }
      wall += now() - t0;
      std::fprintf(stderr, "\r  %zu^2 grid: seed %d/%d", n, s + 1, seeds);
    }
    std::fprintf(stderr, "\n");
    nlohmann::json curve = nlohmann::json::array();
    for (std::size_t k = 0; k < sigmas.size(); ++k) curve.push_back({{"sigma_star", sigmas[k]}, {"area_fraction", area[k]}});
    rows.push_back({{"n", n}, {"band_n", period_effect ? n : band_n}, {"period_effect", period_effect},
                    {"period", period_effect ? 1e-2 * double(n) / double(sizes.front()) : 1e-2}, {"seeds", seeds}, {"rms_slope", slope_mean}, {"kappa", kappa},
                    {"curve", curve}, {"wall_s", wall}});
  }
  return rows;
}

}  // namespace wr::bench

namespace wr::bench {

void plot_kappa(const nlohmann::json& rows, const std::string& path) {
  PlotSpec p;
  const bool period = !rows.empty() && rows[0].value("period_effect", false);
  p.title = period ? "Spectral half-space: A/A0 against sigma*, period growing at fixed spacing"
                   : "Spectral half-space: A/A0 against sigma* on finer grids of one band-limited surface";
  p.xlabel = "sigma* = p / (E* rms slope)";
  p.ylabel = "A/A0";
  p.logx = p.logy = true;
  std::vector<double> s_all;
  for (const auto& r : rows) {
    PlotSeries s;
    s.label = std::to_string(r["n"].get<std::size_t>()) + "^2 grid (kappa " + std::to_string(r["kappa"].get<double>()).substr(0, 5) + ")";
    for (const auto& c : r["curve"]) {
      s.x.push_back(c["sigma_star"].get<double>());
      s.y.push_back(c["area_fraction"].get<double>());
    }
    s_all = s.x;
    p.series.push_back(s);
  }
  if (!s_all.empty()) {
    PlotSeries persson{"Persson kappa 1.60", {s_all.front(), s_all.back()}, {}, "lines", {}};
    PlotSeries bgt{"BGT kappa 2.51", {s_all.front(), s_all.back()}, {}, "lines", {}};
    for (double x : persson.x) {
      persson.y.push_back(kappa_persson() * x);
      bgt.y.push_back(kappa_bgt() * x);
    }
    p.series.push_back(persson);
    p.series.push_back(bgt);
  }
  write_svg_plot(path, p);
}


}  // namespace wr::bench
