// Compliance of small contact spots, FEM bricks against spectral pixels (bench/bench_harness.hpp).
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
