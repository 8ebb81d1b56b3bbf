#pragma once
// `wetroad bench sliding` and `wetroad bench sliding-convergence`: the exact rung of the hysteresis
// friction (lib/spectral/viscoelastic_sliding.hpp) against Persson's theory on the same maps.
//
// Scene: the default scene's surface (30 mm tile, h0 0.3 mm, H 0.7, q0 = 5 qL), band-limited to
// q1 = `band` qL so that the grid resolves the shortest wavelength with n / band points; the default
// compound, isothermal (no flash temperature), sliding along x. Persson's mu(v) and A/A0 come from
// the map's own radial PSD on the same band [qL, q1] (no extrapolation).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr::bench {

struct SlidingBenchSetup {
  std::size_t n = 512;
  std::vector<std::uint64_t> seeds = {1, 2, 3};
  std::vector<double> pressures = {0.1e6, 0.3e6};  // Pa
  double band = 64;                                // q1 / qL
  double h0 = 3e-4;                                // m
  double speed_min = 1e-6, speed_max = 10;         // m/s
  int per_decade = 2;                              // speeds per decade
  double temperature = 20;                         // deg C
  double tolerance = 1e-8;
  int threads = 0;
  std::string compound;                            // "" = the default compound
};

// Rows {seed, pressure, v, mu, mu_dissipation, identity_residual, area_fraction, mu_persson,
// area_persson, iterations, fft_pairs, wall_s, converged, bands [{q_low, q_high, exact, persson}]},
// a summary per (pressure, v) over the seeds, memory_bytes and peak_rss_bytes.
nlohmann::json sliding_against_persson(const SlidingBenchSetup& s);

// The same band on grids of `sizes` points per side (ascending, each the double of the one before)
// for one seed and pressure at `speeds`: mu per grid and Richardson's extrapolation and error
// estimate from the last three.
nlohmann::json sliding_grid_convergence(const SlidingBenchSetup& s, const std::vector<std::size_t>& sizes,
                                        const std::vector<double>& speeds);

}  // namespace wr::bench
