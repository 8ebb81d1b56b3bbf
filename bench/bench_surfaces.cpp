// Benchmarks of the surface and water modules, Hertz and summit statistics (bench/bench_harness.hpp).
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
