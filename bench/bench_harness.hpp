#pragma once
// Benchmarks and long validations behind `wetroad bench ...` (never run by `make test`).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr::bench {

// synth + analyze of an N x N surface, in-process, in a forked child per size so that the peak
// resident memory of each size is its own. Reports the best of `repeats` wall times per phase.
nlohmann::json speed(const std::vector<std::size_t>& sizes, int repeats, int threads, bool with_files,
                     const std::string& scratch_dir);

// Summit statistics of ensembles of synthesized surfaces (thesis Fig. 4.4): for each low-pass
// fraction of dataset C, `realizations` surfaces; ensemble mean of the measured summit mean and
// variance against eq. 4.5 at the prescribed alpha. Progress lines go to stderr.
nlohmann::json summit_ensemble(const std::vector<double>& fractions, int realizations, int threads);

// Water on an N x N default-like surface, single-threaded code paths: drained limit, hierarchy
// build, further rain depths, coverage bisection; cells per second; peak memory (forked child).
nlohmann::json water_speed(std::size_t n, int rain_depths);

// Drained-limit coverage of the default asphalt-like surface over `seeds` realizations for
// 4- and 8-connectivity (exact torus and the thesis's 3x3 tiling).
nlohmann::json water_limit_coverage(int seeds);

// Hertz validation of the FEM contact solver (PETSc must be initialised): a paraboloid
// obstacle (radius R) pressed into an elastic block on meshes of n x n elements per face;
// compares the contact radius with Hertz's for the computed force, a = (3 F R / (4 E*))^(1/3),
// and reports the observed convergence order. `layers_per_level` grades the bulk (graded_mesh.hpp):
// with 2 the spacing at depth z is about z/2 whatever n, so the bulk field does not refine with n.
// Progress lines go to stderr on `rank` 0 only.
nlohmann::json hertz(const std::vector<int>& meshes, double radius, double uz, int layers_per_level, int rank);

}  // namespace wr::bench
