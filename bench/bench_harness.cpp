#include "bench/bench_harness.hpp"

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

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

LoadedSurface as_loaded(SynthResult&& r) {
  LoadedSurface s;
  s.source = "(in memory)";
  s.format = "memory";
  s.dropout.assign(r.map.h.size(), 0);
  s.synthesis = SynthesisRecord{r.psd, r.k_eq44, r.h0_eq44_on_lattice, 1, 1};
  s.map = std::move(r.map);
  return s;
}

nlohmann::json speed_one(std::size_t n, int repeats, int threads, bool with_files, const std::string& dir) {
  double best_synth = 1e300, best_analyze = 1e300, best_write = 1e300, best_read = 1e300, best_total = 1e300;
  nlohmann::json phases;
  for (int rep = 0; rep < repeats; ++rep) {
    SynthParams p;
    p.nx = p.ny = n;
    p.dx = 0.03 / n;
    p.h0 = 3e-4;
    p.threads = threads;
    p.seed = 1 + rep;
    const double t0 = now();
    SynthResult r = synthesize(p);
    const double t1 = now();
    double tw = 0, tr = 0;
    LoadedSurface s;
    if (with_files) {
      const std::string path = dir + "/bench-" + std::to_string(n) + ".h5";
      write_surface_file(path, r.map, SynthesisRecord{r.psd, r.k_eq44, r.h0_eq44_on_lattice, p.seed, 1}, {});
      const double t2 = now();
      r = SynthResult{};
      s = load_surface(path);
      tr = now() - t2;
      tw = t2 - t1;
      std::filesystem::remove(path);
    } else {
      s = as_loaded(std::move(r));
    }
    const double t3 = now();
    AnalysisOptions opt;
    opt.threads = threads;
    const AnalysisReport rep_ = analyze_surface(s, opt);
    const double t4 = now();
    const double total = (t1 - t0) + tw + tr + (t4 - t3);
    if (total < best_total) phases = rep_.timer.to_json();
    best_synth = std::min(best_synth, t1 - t0);
    best_analyze = std::min(best_analyze, t4 - t3);
    best_write = std::min(best_write, tw);
    best_read = std::min(best_read, tr);
    best_total = std::min(best_total, total);
  }
  const double map_bytes = double(n) * double(n) * sizeof(double);
  const double rss = double(peak_rss_bytes());
  return {{"n", n},
          {"synth_s", best_synth},
          {"analyze_s", best_analyze},
          {"write_s", best_write},
          {"read_s", best_read},
          {"total_s", best_total},
          {"analyze_phases_s", phases},
          {"peak_rss_bytes", rss},
          {"map_bytes", map_bytes},
          {"peak_rss_over_map", rss / map_bytes},
          {"repeats", repeats},
          {"threads", threads}};
}

}  // namespace

namespace {

// Runs f() in a forked child and returns its JSON, so that the peak memory it reports is its own.
template <class F>
nlohmann::json in_child(F f) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    std::string s;
    try {
      s = f().dump();
    } catch (const std::exception& e) {
      s = nlohmann::json{{"error", e.what()}}.dump();
    }
    const char* p = s.data();
    std::size_t left = s.size();
    while (left > 0) {
      const ssize_t w = write(fd[1], p, left);
      if (w <= 0) break;
      p += w;
      left -= static_cast<std::size_t>(w);
    }
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  std::string buf;
  char chunk[4096];
  ssize_t got;
  while ((got = read(fd[0], chunk, sizeof chunk)) > 0) buf.append(chunk, static_cast<std::size_t>(got));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return buf.empty() ? nlohmann::json{{"error", "child failed"}} : nlohmann::json::parse(buf);
}

HeightMap default_like_surface(std::size_t n, std::uint64_t seed) {
  SynthParams p;  // default scene's spectrum (h0 0.3 mm, H 0.7, q0 = 5 qL), 0.1 mm spacing
  p.nx = p.ny = n;
  p.dx = 1e-4;
  p.h0 = 3e-4;
  p.hurst = 0.7;
  p.seed = seed;
  return synthesize(p).map;
}

}  // namespace

nlohmann::json speed(const std::vector<std::size_t>& sizes, int repeats, int threads, bool with_files,
                     const std::string& scratch_dir) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t n : sizes) {
    nlohmann::json r = in_child([&] { return speed_one(n, repeats, threads, with_files, scratch_dir); });
    r["n"] = n;
    out.push_back(r);
  }
  return out;
}

nlohmann::json water_speed(std::size_t n, int rain_depths) {
  return in_child([&] {
    const HeightMap m = default_like_surface(n, 1);
    const double cells = double(m.h.size());
    double t0 = now();
    const BigVector lim = drained_limit_levels(m, 4, Boundary::torus);
    const double t_limit = now() - t0;
    t0 = now();
    const DepressionHierarchy dh(m, 4, Boundary::torus);
    const double t_build = now() - t0;
    double t_rain = 0, worst = 0;
    for (int k = 0; k < rain_depths; ++k) {
      const double d = 1e-6 * std::pow(4.0, k);
      t0 = now();
      const WaterState w = fill_spill_merge(dh, d, WaterMode::drained);
      const double dt = now() - t0;
      t_rain += dt;
      worst = std::max(worst, dt);
    }
    t0 = now();
    FillRequest req;
    req.coverage = 0.3;
    const FillResult fr = fill_water(m, req);
    const double t_cov = now() - t0;
    return nlohmann::json{{"n", n},
                          {"limit_s", t_limit},
                          {"limit_cells_per_s", cells / t_limit},
                          {"hierarchy_s", t_build},
                          {"hierarchy_cells_per_s", cells / t_build},
                          {"hierarchy_nodes", dh.nodes().size()},
                          {"rain_mean_s", t_rain / rain_depths},
                          {"rain_worst_s", worst},
                          {"rain_cells_per_s", cells * rain_depths / t_rain},
                          {"coverage_target_s", t_cov},
                          {"peak_rss_bytes", double(peak_rss_bytes())}};
  });
}

nlohmann::json water_limit_coverage(int seeds) {
  nlohmann::json rows = nlohmann::json::array();
  for (int conn : {4, 8}) {
    std::vector<double> exact, tiled, differ;
    for (int s = 1; s <= seeds; ++s) {
      const HeightMap m = default_like_surface(300, std::uint64_t(s));
      FillRequest req;
      req.limit = true;
      req.connectivity = conn;
      const FillResult e = fill_water(m, req);
      req.tiling = Tiling::three_by_three;
      const FillResult t = fill_water(m, req);
      exact.push_back(e.water.coverage);
      tiled.push_back(t.water.coverage);
      differ.push_back(double(t.tiling_differing_cells.value_or(0)));
      std::fprintf(stderr, "\r  connectivity %d: %d/%d surfaces", conn, s, seeds);
    }
    std::fprintf(stderr, "\n");
    auto stats = [](const std::vector<double>& v) {
      double m = 0, s2 = 0;
      for (double x : v) m += x;
      m /= double(v.size());
      for (double x : v) s2 += (x - m) * (x - m);
      return std::pair{m, v.size() > 1 ? std::sqrt(s2 / double(v.size() - 1)) : 0.0};
    };
    const auto [em, es] = stats(exact);
    const auto [tm, ts] = stats(tiled);
    const auto [dm, ds] = stats(differ);
    rows.push_back({{"connectivity", conn},
                    {"seeds", seeds},
                    {"exact_mean", em},
                    {"exact_std", es},
                    {"tiled_3x3_mean", tm},
                    {"tiled_3x3_std", ts},
                    {"tiling_differing_cells_mean", dm},
                    {"exact", exact},
                    {"tiled_3x3", tiled}});
  }
  return rows;
}

nlohmann::json hertz(const std::vector<int>& meshes, double radius, double uz, int layers_per_level, int rank) {
  const double L = 0.02, young = 1.0, nu = 0.45, e_star = young / (1 - nu * nu);
  // The cap on a fine lattice (the triangulated paraboloid deviates from the true one by
  // dx^2 / (8 R), negligible against the indentation).
  const PeriodicObstacle obstacle(paraboloid_cap(512, L, radius));
  nlohmann::json rows = nlohmann::json::array();
  for (int n : meshes) {
    BlockSpec b;
    b.mesh.lx = b.mesh.ly = b.mesh.lz = L;
    b.mesh.nx = b.mesh.ny = n;
    b.mesh.layers_per_level = layers_per_level;
    b.young = young;
    b.poisson = nu;
    const double t0 = now();
    ElasticBlock block(b);
    ContactLoad load;
    load.obstacle = &obstacle;
    load.follow_geometry = false;  // Hertz's linearised (small-slope) geometry
    load.uz = uz;
    load.ksp_rtol = 1e-8;
    load.face_maps = true;
    const ContactSolution s = block.solve(load);
    const double h = L / n;
    const double a_num = std::sqrt(double(s.contact_nodes) * h * h / M_PI);
    const double a_hertz = hertz_radius(s.fz, radius, e_star);
    const HertzFit fit = fit_hertz_pressure(s.face_pressure, n + 1, n + 1, h, L / 2, L / 2, a_num);
    const double a_fit = fit.radius, p0_fit = fit.peak_pressure;
    const double p0_hertz = 3 * s.fz / (2 * M_PI * a_hertz * a_hertz);
    rows.push_back({{"n", n},
                    {"h", h},
                    {"nodes", block.nodes()},
                    {"fz", s.fz},
                    {"contact_nodes", s.contact_nodes},
                    {"a_fem", a_num},
                    {"a_hertz", a_hertz},
                    {"radius_error", a_num / a_hertz - 1},
                    {"a_fit", a_fit},
                    {"p0_fit", p0_fit},
                    {"p0_hertz", p0_hertz},
                    {"fit_radius_error", a_fit / a_hertz - 1},
                    {"fit_p0_error", p0_fit / p0_hertz - 1},
                    {"force_error", s.fz / hertz_force(a_fit, radius, e_star) - 1},
                    {"count_force_error", s.fz / hertz_force(a_num, radius, e_star) - 1},
                    {"converged", s.converged},
                    {"wall_s", now() - t0}});
    if (rank == 0) std::fprintf(stderr, "  mesh %d done (%.1f s)\n", n, now() - t0);
  }
  return rows;
}

nlohmann::json summit_ensemble(const std::vector<double>& fractions, int realizations, int threads) {
  nlohmann::json rows = nlohmann::json::array();
  for (double f : fractions) {
    double sum_mean = 0, sum_var = 0, sum_mean2 = 0, sum_var2 = 0, sum_alpha = 0, sum_density = 0, sum_ks = 0;
    double alpha_prescribed = 0, density_prescribed = 0;
    int n = 0;
    for (int r = 0; r < realizations; ++r) {
      // Thesis dataset C: 300 x 300, dx 0.1 mm, h0 0.71 mm, H 0.7, q1 = 2 pi / dx (needs 2x oversampling).
      SynthParams p;
      p.nx = p.ny = 300;
      p.dx = 1e-4;
      p.h0 = 0.708e-3;
      p.hurst = 0.7;
      p.q1 = 2 * std::numbers::pi / p.dx;
      p.oversample = 2;
      p.q1_fraction = f;
      p.seed = 1000 + static_cast<std::uint64_t>(r);
      p.threads = threads;
      SynthResult sr = synthesize(p);
      LoadedSurface s = as_loaded(std::move(sr));
      AnalysisOptions opt;
      opt.threads = threads;
      opt.expected_mpd = false;
      const AnalysisReport rep = analyze_surface(s, opt);
      if (!rep.summit_mean) continue;
      ++n;
      sum_mean += *rep.summit_mean;
      sum_mean2 += *rep.summit_mean * *rep.summit_mean;
      sum_var += *rep.summit_var;
      sum_var2 += *rep.summit_var * *rep.summit_var;
      sum_alpha += rep.moments.alpha();
      sum_density += *rep.summit_density;
      sum_ks += rep.summit_ks.value_or(0);
      alpha_prescribed = *rep.prescribed.alpha;
      density_prescribed = *rep.prescribed.summit_density;
      if ((r + 1) % 10 == 0 || r + 1 == realizations)
        std::fprintf(stderr, "\r  q1/q1^ = %-6.4g  %3d/%d surfaces", f, r + 1, realizations);
    }
    std::fprintf(stderr, "\n");
    const double mean = sum_mean / n, var = sum_var / n, alpha_meas = sum_alpha / n;
    const auto gw = greenwood_summit_moments(alpha_prescribed);
    const auto gw_meas = greenwood_summit_moments(alpha_meas);
    rows.push_back({{"q1_fraction", f},
                    {"surfaces", n},
                    {"alpha_prescribed", alpha_prescribed},
                    {"alpha_measured", alpha_meas},
                    {"summit_mean", mean},
                    {"summit_mean_sd", std::sqrt(std::max(0.0, sum_mean2 / n - mean * mean))},
                    {"summit_var", var},
                    {"summit_var_sd", std::sqrt(std::max(0.0, sum_var2 / n - var * var))},
                    {"eq45_mean", gw.mean},
                    {"eq45_var", gw.variance},
                    {"eq45_mean_at_measured_alpha", gw_meas.mean},
                    {"eq45_var_at_measured_alpha", gw_meas.variance},
                    {"summit_density", sum_density / n},
                    {"nayak_density_prescribed", density_prescribed},
                    {"ks_distance", sum_ks / n}});
  }
  return rows;
}

}  // namespace wr::bench

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
namespace {

// The comparison scene of spectral_vs_fem and accuracy: 100 x 100, 0.1 mm spacing (1 cm
// period), H 0.7, q0 = 2 qL, seed 3.
HeightMap comparison_scene(double h0) {
  SynthParams sp;
  sp.nx = sp.ny = 100;
  sp.dx = 1e-4;
  sp.h0 = h0;
  sp.hurst = 0.7;
  sp.q0_ratio = 2;
  sp.seed = 3;
  sp.threads = 1;
  return synthesize(sp).map;
}

// Its press: about a third of contact whatever h0 (uz proportional to h0), two steps.
constexpr int kComparisonPressSteps = 2;
constexpr double kComparisonTolerance = 1e-4;
double comparison_uz(double h0) { return 2.5e-4 * h0 / 3e-5; }

// The press as FEM options (the accuracy bench's runs).
ContactTestOptions comparison_press(double h0, int refine, double slope) {
  ContactTestOptions fo;
  fo.uz = comparison_uz(h0);
  fo.normal_steps = kComparisonPressSteps;
  fo.refine = refine;
  fo.tolerance = kComparisonTolerance;
  fo.rms_slope = slope;
  return fo;
}

// The press and then a shear test, as a scene both models run: the top moved by half the
// press in two steps (the face slides several lattice cells on the gentle scenes, about one on
// the steepest).
ContactScene comparison_shear(double h0, int refine) {
  ContactScene sc;
  sc.uz = comparison_uz(h0);
  sc.normal_steps = kComparisonPressSteps;
  sc.ux = sc.uz / 2;
  sc.shear_steps = 2;
  sc.refine = refine;
  sc.tolerance = kComparisonTolerance;
  return sc;
}

// mu of a shear run's last step; NaN when it did not get there.
double final_mu(const SceneResult& r, const ContactScene& sc) {
  const std::size_t n = std::size_t(sc.normal_steps + sc.shear_steps);
  return r.steps.size() == n && !r.failed ? r.steps.back().mu : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

nlohmann::json spectral_vs_fem(const std::vector<double>& h0s, int refine, int rank) {
  nlohmann::json rows = nlohmann::json::array();
  for (double h0 : h0s) {
    const HeightMap m = comparison_scene(h0);
    const double slope = rms_slope_finite_difference(m, 1);
    // One FEM run gives both: A/A0 at the end of its press, mu at the end of its shear.
    ContactScene shear = comparison_shear(h0, refine);
    shear.model = ContactModel::fem;
    double t0 = now();
    const SceneResult fr = run_contact_scene(m, shear, MPI_COMM_NULL);
    const double fem_wall = now() - t0;
    if (fr.steps.empty()) throw std::runtime_error("spectral-vs-fem: no FEM step finished at h0 " + std::to_string(h0) + " m");
    // The press's last step (or the last that finished; fem_converged says which).
    const ContactStep& fs = fr.steps[std::min(fr.steps.size(), std::size_t(shear.normal_steps)) - 1];
    const double fem_mu = final_mu(fr, shear);
    nlohmann::json row = {{"h0", h0}, {"rms_slope", slope}, {"refine", refine}, {"fem_nodes", fr.unknowns},
                          {"fem_fz", fs.fz}, {"fem_area_fraction", fs.area_fraction}, {"fem_converged", !fr.failed},
                          {"fem_wall_s", fem_wall}, {"uz", shear.uz}, {"ux", shear.ux}, {"fem_mu", fem_mu}};
    if (rank == 0) {
      // The spectral layer (thickness = the period) at the FEM's mean pressure, on the same face lattice.
      SpectralTestOptions so;
      so.pressure = fs.fz / (m.lx() * m.ly());
      so.steps = 2;
      so.body = ElasticBody{shear.young, shear.poisson, m.lx()};
      so.rms_slope = slope;
      so.solver.threads = 1;
      t0 = now();
      const SpectralTestResult r = run_spectral_contact_test(resample_triangulated(m, refine), so);
      row["spectral_area_fraction"] = r.steps.back().area_fraction;
      row["spectral_converged"] = !r.failed;
      row["spectral_wall_s"] = now() - t0;
      row["area_difference"] = r.steps.back().area_fraction / fs.area_fraction - 1;
      // mu compared at equal displacements: the layer is stiffer than the cube at equal uz,
      // but a frictionless mu does not scale with the load, and equal pressure cannot be set
      // under displacement control.
      t0 = now();
      shear.model = ContactModel::spectral;  // on the FEM's face lattice, a layer as thick as the cube
      const SceneResult rs = run_contact_scene(m, shear, MPI_COMM_NULL);
      const double spectral_mu = final_mu(rs, shear);
      row["spectral_shear_converged"] = !rs.failed;
      row["spectral_shear_wall_s"] = now() - t0;
      row["spectral_mu"] = spectral_mu;
      // mu of a frictionless contact is a mean of local slopes weighted by pressure, so its
      // scale is the rms slope: the difference is reported relative to it.
      row["mu_difference_per_slope"] = (spectral_mu - fem_mu) / slope;
      std::fprintf(stderr, "  h0 %.3g m (rms slope %.3f) done: FEM %.1f s\n", h0, slope, fem_wall);
    }
    rows.push_back(row);
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

void plot_spectral_vs_fem(const nlohmann::json& rows, const std::string& path) {
  PlotSpec p;
  p.title = "Spectral layer against the FEM block: A/A0 at equal mean pressure, mu at equal displacements";
  p.xlabel = "rms slope";
  p.ylabel = "difference, %";
  const std::string refine = "refine " + std::to_string(rows.empty() ? 0 : rows[0]["refine"].get<int>());
  PlotSeries area{"A/A0: spectral / FEM - 1, " + refine, {}, {}, "linespoints", {}};
  PlotSeries mu{"mu: (spectral - FEM) / rms slope, " + refine, {}, {}, "linespoints", {}};
  for (const auto& r : rows) {
    area.x.push_back(r["rms_slope"].get<double>());
    area.y.push_back(100 * r["area_difference"].get<double>());
    mu.x.push_back(r["rms_slope"].get<double>());
    mu.y.push_back(100 * r["mu_difference_per_slope"].get<double>());
  }
  p.series.push_back(area);
  p.series.push_back(mu);
  write_svg_plot(path, p);
}

}  // namespace wr::bench

namespace wr::bench {

nlohmann::json accuracy(double h0, const std::vector<int>& fem_refines, const std::vector<int>& spectral_refines,
                        int rank) {
  const HeightMap m = comparison_scene(h0);
  const double slope = rms_slope_finite_difference(m, 1), a0 = m.lx() * m.ly();
  nlohmann::json points = nlohmann::json::array();
  // FEM first (displacement-controlled: its mean pressure moves a little with the mesh); the
  // finest FEM's mean pressure is the load of the spectral and analytic points, so that they
  // meet the reference at equal load.
  double pressure = 0;
  for (int r : fem_refines) {
    const ContactTestOptions fo = comparison_press(h0, r, slope);
    const double t0 = now();
    const ContactTestResult fr = run_contact_test(m, fo);
    const ContactStep& st = fr.steps.back();
    pressure = st.fz / a0;
    points.push_back({{"model", "fem"}, {"refine", r}, {"nodes", fr.nodes}, {"pressure", st.fz / a0},
                      {"area_fraction", st.area_fraction}, {"wall_s", now() - t0}, {"converged", !fr.failed}});
    if (rank == 0) std::fprintf(stderr, "  fem refine %d: %.1f s\n", r, now() - t0);
  }
  if (rank == 0) {
    for (int r : spectral_refines) {
      SpectralTestOptions so;
      so.pressure = pressure;
      so.steps = 2;
      so.body = ElasticBody{1.0, 0.45, m.lx()};
      so.rms_slope = slope;
      so.solver.threads = 1;
      const double t0 = now();
      const HeightMap fine = resample_triangulated(m, r);
      const SpectralTestResult res = run_spectral_contact_test(fine, so);
      points.push_back({{"model", "spectral"}, {"refine", r}, {"nodes", fine.size()}, {"pressure", pressure},
                        {"area_fraction", res.steps.back().area_fraction}, {"wall_s", now() - t0},
                        {"converged", !res.failed}});
    }
    const double t0 = now();
    const double sigma = pressure / (1.0 / (1 - 0.45 * 0.45) * slope);
    points.push_back({{"model", "analytic"}, {"refine", 0}, {"nodes", 0}, {"pressure", pressure},
                      {"area_fraction", persson_area_fraction(sigma)}, {"wall_s", std::max(now() - t0, 1e-7)},
                      {"converged", true}});
    // The reference: the finest FEM (the last in the list); errors of A/A0 against it.
    double ref = 0;
    for (const auto& p : points)
      if (p["model"] == "fem") ref = p["area_fraction"].get<double>();
    for (auto& p : points) p["error"] = std::abs(p["area_fraction"].get<double>() / ref - 1);
  }
  return {{"h0", h0}, {"rms_slope", slope}, {"reference", "finest FEM"}, {"points", points}};
}

void plot_accuracy(const nlohmann::json& result, const std::string& path) {
  PlotSpec p;
  p.title = "A/A0 of one scene: wall time against the error to the finest FEM";
  p.xlabel = "wall time, s";
  p.ylabel = "|A/A0 / A/A0(finest FEM) - 1|";
  p.logx = p.logy = true;
  for (const char* model : {"analytic", "spectral", "fem"}) {
    PlotSeries s{model, {}, {}, "linespoints", {}};
    for (const auto& q : result["points"])
      if (q["model"] == model && q["error"].get<double>() > 0) {
        s.x.push_back(q["wall_s"].get<double>());
        s.y.push_back(q["error"].get<double>());
      }
    if (!s.x.empty()) p.series.push_back(s);
  }
  write_svg_plot(path, p);
}

}  // namespace wr::bench

namespace wr::bench {
namespace {

// Nodes per face node of the graded cube (300 x 300 obstacle: 2.90 at refine 2, 2.73 at
// refine 4) and the share of memory up to which a lean-hierarchy run is tried (300 x 300 at
// refine 4: 3.93M nodes ran in 19.5 GiB of 23.5 GiB, 83 %); with fem_memory_estimate a pre-flight
// check that decides whether a mesh is tried. The block picks its hierarchy itself (automatic).
constexpr double kNodesPerFaceNode = 2.8, kLeanMemoryShare = 0.9;

double estimated_fem_bytes(const HeightMap& m, int refine, double memory) {
  const double face = double(m.nx * std::size_t(refine) + 1) * double(m.ny * std::size_t(refine) + 1);
  const double nodes = kNodesPerFaceNode * face;
  return fem_memory_estimate(nodes, resolve_amg_hierarchy(AmgHierarchy::automatic, nodes, memory));
}

}  // namespace

nlohmann::json fem_mesh_convergence(const HeightMap& surface, const ContactScene& base, const std::vector<int>& refines,
                                    int rank) {
  nlohmann::json rows = nlohmann::json::array();
  const double memory = double(physical_memory_bytes());
  for (int r : refines) {
    ContactScene sc = base;
    sc.model = ContactModel::fem;
    sc.refine = r;
    const double need = estimated_fem_bytes(surface, r, memory);
    nlohmann::json row = {{"refine", r}, {"face_spacing", surface.dx / r}, {"estimated_bytes", need}};
    if (need > kLeanMemoryShare * memory) {
      row["skipped"] = "estimated " + human_bytes(need) + " of " + human_bytes(memory) + " physical memory";
      if (rank == 0) std::fprintf(stderr, "  refine %d skipped: %s\n", r, row["skipped"].get<std::string>().c_str());
      rows.push_back(row);
      continue;
    }
    const double t0 = now();
    const SceneResult fr = run_contact_scene(surface, sc, MPI_COMM_NULL);
    row["wall_s"] = now() - t0;
    row["nodes"] = fr.unknowns;
    row["converged"] = !fr.failed;
    row["peak_rss_bytes"] = double(peak_rss_bytes());  // this process so far (rank 0 reports its own)
    if (fr.area_normal > 0) row["pressed_area_fraction"] = fr.area_normal;
    if (const ContactStep* p = peak_friction(fr.steps)) {
      row["mu"] = p->mu;
      row["mu_ux"] = p->ux;
      row["mu_drift"] = p->mu_drift;
      // The iteration met --tol while mu still crept (friction_convergence.hpp): such a mu is
      // where the iteration stopped, so the extrapolation that uses it says so.
      row["friction_converged"] = !(p->mu_drift > kFrictionDriftLimit);
      row["sheared_area_fraction"] = p->area_fraction;
    }
    if (fr.failed) row["message"] = fr.message;
    if (rank == 0)
      std::fprintf(stderr, "  refine %d: %zu nodes, %.1f s%s\n", r, fr.unknowns, now() - t0, fr.failed ? ", FAILED" : "");
    rows.push_back(row);
  }
  // Richardson over each run of three successive finished meshes with one refinement ratio.
  nlohmann::json extrapolations = nlohmann::json::array();
  for (std::size_t k = 2; k < rows.size(); ++k) {
    const nlohmann::json &a = rows[k - 2], &b = rows[k - 1], &c = rows[k];
    const double ratio = double(b["refine"].get<int>()) / a["refine"].get<int>();
    if (std::abs(double(c["refine"].get<int>()) / b["refine"].get<int>() - ratio) > 1e-12 || ratio <= 1) continue;
    nlohmann::json e = {{"refines", {a["refine"], b["refine"], c["refine"]}}, {"ratio", ratio}};
    for (const char* q : {"mu", "pressed_area_fraction", "sheared_area_fraction"}) {
      if (!a.contains(q) || !b.contains(q) || !c.contains(q)) continue;
      const auto r = richardson_three(a[q].get<double>(), b[q].get<double>(), c[q].get<double>(), ratio);
      e[q] = r ? nlohmann::json{{"order", r->order}, {"limit", r->limit}, {"error", r->error}}
               : nlohmann::json{{"asymptotic", false}};
      // Beside the verdict, how far the two finest meshes still are apart: a sign change of a
      // difference far below the previous one is convergence within it, not divergence.
      e[q]["finest_difference"] = std::abs(c[q].get<double>() - b[q].get<double>());
    }
    if (e.contains("mu"))
      e["mu"]["friction_converged"] = a.value("friction_converged", false) && b.value("friction_converged", false) &&
                                      c.value("friction_converged", false);
    extrapolations.push_back(e);
  }
  return {{"meshes", rows}, {"extrapolations", extrapolations}};
}

void plot_mesh_convergence(const nlohmann::json& result, const std::string& path) {
  PlotSpec p;
  p.title = "FEM shear test: peak mu against face spacing";
  p.xlabel = "face spacing / obstacle spacing";
  p.ylabel = "mu";
  p.logx = true;
  PlotSeries s{"peak mu (converged meshes)", {}, {}, "linespoints", {}};
  for (const auto& r : result["meshes"])
    if (r.contains("mu") && r.value("converged", false)) {
      s.x.push_back(1.0 / r["refine"].get<int>());
      s.y.push_back(r["mu"].get<double>());
    }
  p.series.push_back(s);
  // The finest extrapolation that found a limit, drawn left of the finest mesh with its GCI band.
  const auto& ex = result["extrapolations"];
  for (auto e = ex.rbegin(); e != ex.rend() && !s.x.empty(); ++e) {
    if (!e->contains("mu") || !(*e)["mu"].contains("limit")) continue;
    const auto& k = (*e)["refines"];
    const std::string label = "Richardson limit over refine " + std::to_string(k[0].get<int>()) + ", " +
                              std::to_string(k[1].get<int>()) + ", " + std::to_string(k[2].get<int>()) + " (GCI band)";
    p.series.push_back({label, {s.x.back() / 2}, {(*e)["mu"]["limit"].get<double>()}, "points",
                        {(*e)["mu"]["error"].get<double>()}});
    break;
  }
  write_svg_plot(path, p);
}

}  // namespace wr::bench

namespace wr::bench {
namespace {

constexpr std::size_t kSpotGrid = 64;    // obstacle samples per side
constexpr double kSpotSpacing = 1e-4;    // m
constexpr double kSpotRise = 1e-5;       // m, the raised vertices above the flat rest
constexpr double kSpotApproach = 1e-7;   // m, 1 % of the rise: nothing else comes into contact

// Flat, with a k x k square of vertices raised in the middle: a flat-topped spot of k x k
// obstacle vertices ((k - 1) r + 1 face nodes per side at refine r).
HeightMap spot_obstacle(int k) {
  HeightMap m(kSpotGrid, kSpotGrid, kSpotSpacing, kSpotSpacing);
  m.periodic = true;
  const std::size_t first = kSpotGrid / 2 - std::size_t(k) / 2;
  for (std::size_t iy = first; iy < first + std::size_t(k); ++iy)
    for (std::size_t ix = first; ix < first + std::size_t(k); ++ix) m(ix, iy) = kSpotRise;
  return m;
}

}  // namespace

nlohmann::json contact_spot(const std::vector<int>& spots, const std::vector<int>& refines, int layers, int rank) {
  constexpr double young = 1.0, poisson = 0.45;
  const double side = double(kSpotGrid) * kSpotSpacing, area = side * side;
  const double m_modulus = young * (1 - poisson) / ((1 + poisson) * (1 - 2 * poisson));  // uniaxial strain
  nlohmann::json rows = nlohmann::json::array();
  for (int k : spots) {
    const HeightMap m = spot_obstacle(k);
    for (int refine : refines) {
      ContactTestOptions fo;
      fo.uz = kSpotApproach;
      fo.normal_steps = 1;
      fo.refine = refine;
      fo.layers_per_level = layers;
      fo.young = young;
      fo.poisson = poisson;
      fo.tolerance = 1e-6;
      fo.rms_slope = 1;  // sigma* is not used here; any positive normalisation
      double t0 = now();
      const ContactTestResult fr = run_contact_test(m, fo);
      const double fem_wall = now() - t0;
      if (fr.failed || fr.steps.empty())
        throw std::runtime_error("bench spot: the FEM step did not converge (spot " + std::to_string(k) + ", refine " +
                                 std::to_string(refine) + ")");
      const ContactStep& fs = fr.steps.back();
      const double fem_local = kSpotApproach / fs.fz - side / (young * area);
      nlohmann::json row = {{"spot_vertices", k},
                            {"refine", refine},
                            {"layers", layers},
                            {"fem_nodes", fr.nodes},
                            {"fem_fz", fs.fz},
                            {"fem_contact_nodes", std::llround(fs.area_fraction * double(fr.face_nodes))},
                            {"fem_local_compliance", fem_local},
                            {"fem_wall_s", fem_wall}};
      if (rank == 0) {
        SpectralTestOptions so;
        so.uz = kSpotApproach;
        so.steps = 1;
        so.body = ElasticBody{young, poisson, side};
        so.rms_slope = 1;
        so.solver.threads = 1;
        t0 = now();
        const HeightMap grid = resample_triangulated(m, refine);
        const SpectralTestResult sr = run_spectral_contact_test(grid, so);
        if (sr.failed || sr.steps.empty())
          throw std::runtime_error("bench spot: the spectral step did not converge (spot " + std::to_string(k) + ")");
        const ContactStep& ss = sr.steps.back();
        const double spectral_local = kSpotApproach / ss.fz - side / (m_modulus * area);
        row["spectral_fz"] = ss.fz;
        row["spectral_contact_points"] = std::llround(ss.area_fraction * double(grid.size()));
        row["spectral_local_compliance"] = spectral_local;
        row["spectral_wall_s"] = now() - t0;
        row["local_compliance_ratio"] = fem_local / spectral_local;
        std::fprintf(stderr, "  spot %d x %d, refine %d done (FEM %.1f s)\n", k, k, refine, fem_wall);
      }
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace wr::bench
