#pragma once
// The exact rung of the hysteresis friction as a friction curve: steady viscoelastic sliding
// (lib/spectral/viscoelastic_sliding.hpp) over the road map itself, for the friction scene
// (lib/friction/friction_scene.hpp, `--model viscoelastic`).
//
// The map is first band-limited to the radial band Persson's theory integrates over (|q| <= q_band,
// so that both models see the same roughness) and Fourier-interpolated `refine` times finer: the
// contact spots at the shortest wavelength then span 2 x refine grid points (refine 4: mu within
// about 2 % of the grid-converged value, docs/validation.md "The exact rung"). Speeds are solved
// in ascending order, each from the previous one's pressure. Isothermal (no flash temperature),
// sliding along x.
#include <cstddef>
#include <string>
#include <vector>

#include "lib/core/height_map.hpp"
#include "lib/friction/compound.hpp"
#include "lib/friction/hysteresis_friction.hpp"

namespace wr {

constexpr std::size_t kDefaultExactRefine = 4;

struct ExactStats {
  std::size_t nx = 0, ny = 0;     // the solver's grid
  std::size_t refine = 0;
  double q_band = 0;              // 1/m
  int max_iterations = 0;         // the most any speed took
  bool converged = true;          // at every speed
  std::string message;            // the first speed's failure, if any
  double max_identity_residual = 0;  // largest |mu_dissipation - mu| / mu over the speeds
  double wall_s = 0;              // all speeds
  int solves = 0;
  std::size_t memory_bytes = 0;   // the solver's arrays
};

// mu(v) and A/A0 by the exact rung at `speeds` (m/s, > 0; any order: the results follow it), under
// opt.pressure at opt.temperature. FrictionPoint's temperature_rise and mu_extrapolated are 0.
// `progress`: print one line per speed to stderr. InputError for a map that is not periodic
// or too large for memory; the solver's failures are reported in `stats`, not thrown.
std::vector<FrictionPoint> exact_friction_curve(const HeightMap& map, double q_band, std::size_t refine,
                                                const Compound& compound, const FrictionOptions& opt,
                                                const std::vector<double>& speeds, ExactStats& stats, bool progress);

}  // namespace wr
