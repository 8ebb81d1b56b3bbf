#pragma once
// Thin-film (Reynolds) flow of an incompressible fluid through the gap of a rough contact, on the
// map: the effective conductance tensor of the gap field, the flow factors of Patir & Cheng
// (ASME J. Lubr. Technol. 100, 12 (1978)) computed on the whole periodic map as Dapp, Lücke,
// Persson & Müser do (PRL 108, 244301 (2012)).
//
// Physics. Steady Reynolds equation for the pressure p in a gap g(x, y) >= 0 (m), viscosity eta:
//   div( g^3 / (12 eta) grad p ) = 0,   p = -G.x + p~,  p~ periodic,
// G the imposed mean pressure gradient (Pa/m). The mean volume flux per unit width is
// J = -(K / eta) G with K the effective conductance (m^3, symmetric, positive semi-definite);
// parallel plates at gap g give K = g^3/12 identity.
//
// Discretisation. Cell-centred finite volumes on the map's grid (a value of `gap` is the gap over
// the cell dx x dy around its sample), 5-point stencil. The conductance of the face between two
// cells is the harmonic mean of their g^3/12: series resistances, so a contact cell (g = 0) shuts
// its four faces. K follows from two solves, G = e_x and G = e_y, with one factorisation.
// With this choice the discrete K of a 1-D corrugation g(x) is exact for the sampled cells: along
// the ridges (y) K_yy = the arithmetic mean of the cells' g^3/12, across them (x) K_xx = the
// harmonic mean. Against the continuum means of a profile those are rectangle-rule quadratures:
// spectrally convergent in the grid for a smooth periodic profile, second order (or the order of
// the profile's roughest kink) for a profile with kinks, such as a triangle wave. For a 2-D map
// the error against the continuum is that of a 5-point scheme with harmonic face averages
// (second order where g is smooth and positive; first order at the contact lines, where g^3/12
// drops to 0 over one cell).
//
// Topology. Cells with g > 0 are free; two free cells sharing a face are connected
// (4-connectivity; periodic). A free cluster carries a mean flux in x only if it contains a cycle
// that winds around the torus in x (it "percolates in x"); a cluster that winds in no direction,
// and every contact cell, carries none. Their unknowns are left out of the system, and one
// unknown per winding cluster is pinned (p~ = 0 there), so the system is symmetric positive
// definite. When no cluster winds in x, K_xx = K_xy = K_yx = 0 exactly (likewise for y).
//
// Solvers. CHOLMOD's supernodal Cholesky (SuiteSparse; direct: residual at round-off), or PETSc's
// CG preconditioned by GAMG (smoothed-aggregation AMG; to FlowOptions::tolerance, the relative
// residual |b - A x| / |b|). The amg solver needs PETSc started in the process
// (lib/fem/petsc_session.hpp); its KSP reads options under the prefix "flow_" (e.g.
// -flow_ksp_monitor). `automatic` takes the solver measured faster (docs/performance.md,
// "Thin-film flow on the map"): CHOLMOD at every size measured.
#include <string>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

enum class FlowSolver { automatic, cholmod, amg };

// "auto", "cholmod", "amg"; InputError(option, ...) for anything else.
FlowSolver parse_flow_solver(const std::string& text, const std::string& option);
const char* flow_solver_name(FlowSolver s);  // "auto", "cholmod", "amg"

struct FlowOptions {
  FlowSolver solver = FlowSolver::automatic;
  double tolerance = 1e-10;  // relative residual of an iterative solve (amg); in (0, 1)
  int threads = 0;  // >= 0; not used by the solvers built so far (CHOLMOD's BLAS and PETSc run as configured)
};

struct FlowConductance {
  // Effective conductance tensor K (m^3): the mean volume flux per unit width is
  // J_i = -(K_ij / eta) <d p / d x_j>; parallel plates at gap g give K = g^3/12 * identity.
  double kxx = 0, kxy = 0, kyx = 0, kyy = 0;
  double free_fraction = 0;  // fraction of grid points with gap > 0
  double mean_gap = 0;       // m, mean of the gap over all points
  bool percolates_x = false, percolates_y = false;  // a free (gap > 0) cluster winds around the torus in x / y
  std::string solver;        // which solver ran ("cholmod", "amg"; "none" when nothing percolates)
  int iterations = 0;        // 0 for the direct solver; CG iterations of the longer of the two solves
  double residual = 0;       // relative residual |b - A x| / |b|, the larger of the two solves
  double wall_s = 0;         // the whole call: topology, assembly, solves
  std::size_t unknowns = 0;  // cells in winding clusters, less one pinned per cluster
};

// The flow of the solve with G = e_x (1 Pa/m) and eta = 1 Pa s, row-major like the gap:
// pressure p = -x + p~ (Pa; NaN in cells no through-flow reaches: contact cells and clusters that
// wind in no direction, where p is any constant), flux_x / flux_y the volume flux per unit width
// (m^2/s) averaged from the cell's two faces in that direction. The cell mean of flux_x is K_xx,
// that of flux_y is K_yx.
struct FlowField {
  std::vector<double> pressure, flux_x, flux_y;
};

// gap: a periodic HeightMap (nx, ny >= 1; dx, dy > 0) whose values are the local gap g >= 0 (m).
// Throws InputError("gap", ...) for a negative or non-finite gap, a non-periodic or empty map;
// std::logic_error for amg without PETSc started; NumericalError when a solve fails (CHOLMOD
// finds the matrix not positive definite, CG does not reach the tolerance).
FlowConductance thin_film_conductance(const HeightMap& gap, const FlowOptions& opt, FlowField* field_x = nullptr);

struct Percolation {
  bool x = false, y = false;
};
// Whether the free area (gap > 0, 4-connected, periodic) winds around the torus in x / y: the
// topological part of thin_film_conductance, without a linear solve. Same errors for bad maps.
Percolation free_area_percolation(const HeightMap& gap);

}  // namespace wr
