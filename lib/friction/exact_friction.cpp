#include "lib/friction/exact_friction.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "lib/core/errors.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/spectral/viscoelastic_sliding.hpp"
#include "roads/band_limit.hpp"

namespace wr {

std::vector<FrictionPoint> exact_friction_curve(const HeightMap& map, double q_band, std::size_t refine,
                                                const Compound& compound, const FrictionOptions& opt,
                                                const std::vector<double>& speeds, ExactStats& stats, bool progress) {
  if (!map.periodic) throw InputError("--model", "the viscoelastic model slides over a periodic map (synthesized or made periodic)");
  if (refine < 1 || refine > 16) throw InputError("--exact-refine", "must lie in 1 ... 16");
  const std::size_t cells = map.nx * refine * map.ny * refine;
  // About 21 grid arrays of doubles with the default GCR window (ViscoelasticSliding::memory_bytes).
  require_memory(cells, sizeof(double), 22, "--exact-refine",
                 "the viscoelastic model on a " + std::to_string(map.nx * refine) + "x" + std::to_string(map.ny * refine) + " grid");
  const HeightMap fine = band_limited(map, q_band, refine, opt.threads);
  SlidingOptions so;
  so.threads = opt.threads;
  ViscoelasticSliding solver(fine, compound, opt.temperature, so);
  stats.nx = fine.nx;
  stats.ny = fine.ny;
  stats.refine = refine;
  stats.q_band = q_band;
  stats.memory_bytes = solver.memory_bytes();
  std::vector<std::size_t> order(speeds.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return speeds[a] < speeds[b]; });
  std::vector<FrictionPoint> out(speeds.size());
  for (std::size_t k : order) {
    const SlidingResult r = solver.solve(speeds[k], opt.pressure);
    FrictionPoint& p = out[k];
    p.v = speeds[k];
    p.mu = r.mu;
    p.area_fraction = r.area_fraction;
    stats.max_iterations = std::max(stats.max_iterations, r.iterations);
    stats.max_identity_residual = std::max(stats.max_identity_residual, r.identity_residual);
    stats.wall_s += r.wall_s;
    ++stats.solves;
    if (!r.converged && stats.converged) {
      stats.converged = false;
      stats.message = "at v = " + std::to_string(speeds[k]) + " m/s: " + r.message;
    }
    if (progress)
      std::fprintf(stderr, "  exact rung %zux%zu: v %.3g m/s  mu %.4f  A/A0 %.4g  %d iterations  %.2f s%s\n", fine.nx, fine.ny,
                   speeds[k], r.mu, r.area_fraction, r.iterations, r.wall_s, r.converged ? "" : "  NOT CONVERGED");
  }
  return out;
}

}  // namespace wr
