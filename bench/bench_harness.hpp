#pragma once
// Benchmarks and long validations behind `wetroad bench ...` (never run by `make test`).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"
#include "lib/scene/contact_scene.hpp"

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

// Speed of the spectral normal-contact solver (half-space, load control): on each N x N
// self-affine surface, `loads` mean pressures sigma* = 0.01 ... 0.01 loads, warm-started;
// total wall time, iterations, and the floor beside them (one forward + backward FFT).
nlohmann::json spectral_speed(const std::vector<std::size_t>& sizes, int loads, int threads, double tolerance,
                              int admit_every);

// Speed of the spectral shear test (Problem A then B, sec. 4.2.2) on the n x n self-affine
// surface of spectral_speed: a layer as thick as the period, its far face pressed by uz and then
// moved by ux, `steps` steps each; total wall time, geometry and CG iterations, the FFT-pair
// floor. The friction of the periodic layer is 0 up to lattice effects (translation invariance):
// this measures speed, not mu.
nlohmann::json spectral_shear(std::size_t n, double uz, double ux, int steps, int threads, double tolerance);

// Low-pressure kappa (A/A0 = kappa sigma*, eq. 3.169) and the A/A0(sigma*) curve of the
// spectral half-space on one band-limited self-affine surface per seed (H 0.7, q0 = 5 qL,
// q1 = Nyquist of a band_n grid) sampled on each grid of `sizes`: the grid convergence of
// A/A0 for a fixed continuous surface. Means over `seeds`. Progress on stderr.
// `period_effect`: instead, the spacing of the first size is kept and the period grows with n
// (q1 at every grid's Nyquist wavenumber, q0 = 5 qL of each period): the finite-size effect.
nlohmann::json spectral_kappa(const std::vector<std::size_t>& sizes, std::size_t band_n, int seeds, int threads,
                              bool period_effect);

// Spectral against FEM on small and growing slopes: for each h0, a 100 x 100
// self-affine scene (H 0.7, q0 = 2 qL, period 1 cm) pressed by the FEM block (uz proportional
// to h0, about a third of contact) at face refinement `refine` and then sheared (top moved by
// uz / 2 in two steps); the spectral layer (thickness = the period) pressed to the FEM's mean
// pressure on the same face lattice, and sheared at the FEM's displacements. A/A0 after the
// press and mu after the shear of both; the mu difference also relative to the rms slope (the
// scale of a frictionless mu; both are ~0 on a periodic obstacle, see docs/validation.md).
// PETSc must be initialised; the spectral runs and progress lines on `rank` 0.
nlohmann::json spectral_vs_fem(const std::vector<double>& h0s, int refine, int rank);

// Speed against accuracy on one scene: the spectral_vs_fem scene at h0, the
// FEM at each refine (the finest one's mean pressure is the other models' load), the spectral
// layer at each refine, the analytic model; A/A0 and wall time per point, and the error of
// A/A0 against the finest FEM. PETSc must be initialised; spectral and analytic on `rank` 0.
nlohmann::json accuracy(double h0, const std::vector<int>& fem_refines, const std::vector<int>& spectral_refines,
                        int rank);
void plot_accuracy(const nlohmann::json& result, const std::string& path);

// Mesh convergence of the FEM shear test: `base` (a shear test; its model and
// refine are set here) run by the FEM on
// `surface` at each face refinement in `refines` (ascending; spacing = obstacle spacing /
// refine). A mesh whose estimated memory (fem_memory_estimate with the hierarchy the block
// will pick, lib/fem/amg_hierarchy.hpp) exceeds 90 % of physical memory is skipped and says so. Per mesh: nodes, wall time,
// converged, A/A0 after the press, the peak mu (peak_friction) with its ux, drift and A/A0.
// `extrapolations`: over each three successive meshes with one refinement ratio, Richardson's
// limit, observed order and GCI error (lib/core/richardson.hpp) of mu and both A/A0, or
// "asymptotic": false. Collective over the FEM's ranks; progress lines on `rank` 0.
nlohmann::json fem_mesh_convergence(const HeightMap& surface, const ContactScene& base, const std::vector<int>& refines,
                                    int rank);
void plot_mesh_convergence(const nlohmann::json& result, const std::string& path);

// The compliance of small contact spots (where the bricks' face error comes
// from): a flat 64 x 64 obstacle (0.1 mm spacing) with a k x k square of vertices raised by
// 10 um, touched by the FEM block (cube, E = 1, nu = 0.45, `layers` brick layers per level) and
// by the spectral layer (as thick as the cube) on the same face lattice, the top moved 0.1 um
// (1 % of the rise: the spot stays the raised vertices). Per spot size and refine: Fz and the
// contact nodes of both, and the local compliance of the spot, uz / Fz less the far field
// (the block's uniform compression L / (E A), the layer's L / (M A)); their ratio FEM over
// spectral is what a node of the bricks' face yields against a pixel of uniform pressure.
// PETSc must be initialised; the spectral runs on `rank` 0.
nlohmann::json contact_spot(const std::vector<int>& spots, const std::vector<int>& refines, int layers, int rank);

// Charts of the results above (SVG through gnuplot, reports/plot.hpp).
void plot_kappa(const nlohmann::json& rows, const std::string& path);
void plot_spectral_vs_fem(const nlohmann::json& rows, const std::string& path);

}  // namespace wr::bench
