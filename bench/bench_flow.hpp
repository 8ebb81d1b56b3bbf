#pragma once
// Benchmarks and validation of the thin-film flow on the map (lib/flow/thin_film_flow.hpp), never
// run by `make test`: the solvers' speed, and the percolation threshold of the free area.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"

namespace wr::bench {

// The isotropic self-affine map of the flow benches: n x n points over a 1 cm period, rms height
// 10 um, Hurst `hurst`, roll-off q0 = q0_ratio qL, cut-off q1 = 2 pi / (cells_per_wavelength dx)
// (8: q1 = pi / (4 dx), every wave resolved by 8 points or more).
HeightMap flow_surface(std::size_t n, double hurst, std::uint64_t seed, double q0_ratio, double cells_per_wavelength,
                       int threads);

// On flow_surface(n, 0.8, seed, 4, 8) per size: the spectral half-space (E 10 MPa, nu 0.45) at
// sigma* = sigma0 / (E* rms slope) = `sigma_star`, then the conductance of its gap by CHOLMOD and
// by CG + GAMG (PETSc must be started) timed side by side: rows of n, A/A0, unknowns, each
// solver's wall time, iterations and K, and their largest relative difference.
nlohmann::json flow_speed(const std::vector<std::size_t>& sizes, double sigma_star, std::uint64_t seed, int threads);

struct PercolationSetup {
  std::size_t n = 512;
  std::vector<std::uint64_t> seeds = {1, 2, 3};
  std::vector<double> hursts = {0.3, 0.8};
  double q0_ratio = 4;
  double cells_per_wavelength = 8;
  std::vector<double> ladder = {0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 0.8};  // sigma* of the conductance ladder
  double contact_tolerance = 1e-7;  // the spectral solver's Polonsky-Keer tolerance
  int threads = 0;
};

// Per (seed, H): the contact area fraction at which the free area (gap > 0, 4-connected) stops
// winding around the torus in x and in y, (a) under the elastic half-space (bisection on the
// pressure, in log sigma*, to an area bracket of 0.002) and (b) under a rigid flat (bisection on
// the number of highest points in contact); and for the first seed of each H the conductance
// ladder: A/A0, mean gap, K_xx, K_yy at each sigma*. Progress lines go to stderr.
nlohmann::json percolation_threshold(const PercolationSetup& setup);

}  // namespace wr::bench
