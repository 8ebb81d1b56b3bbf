#pragma once
// Geometric multigrid on the block's own mesh hierarchy, the preconditioner of the active-set
// solves' CG under `--solver gmg` (issue 58; the thesis's own solver was a geometric multigrid,
// sec. 4.3).
//
// Levels: the block's mesh, then the same block meshed with about twice the face spacing
// (GradedMeshSpec nx/2, ny/2, rounded up to even counts: the block at half the refinement), and
// so on while the level is larger than `coarse_nodes`; the last level is assembled and
// factored (sparse Cholesky: CHOLMOD on one rank, MUMPS across ranks) up to `direct_nodes`, else
// given one AMG V-cycle (the thesis scene's coarsest level, 76 x 76 face nodes, would take
// minutes to factor). Every other level applies
// its stiffness without a matrix (MatrixFreeFramed) and is smoothed by Chebyshev polynomials of
// the Jacobi-preconditioned operator (degree `degree`, bounds [lo, hi] x the largest eigenvalue,
// estimated by `estimate_steps` Lanczos steps of CG whenever the frames change). One V-cycle is
// one application: symmetric (same smoother before and after, the restriction the
// prolongation's transpose), so CG may use it.
//
// Transfers: the coarse level's trilinear field evaluated at the fine level's nodes (the meshes
// need not nest: their layers thicken differently, and an odd half is rounded up),
// one scalar AIJ matrix applied to the three components (MAIJ), rotated from and into the levels'
// constraint frames.
//
// Constraints on every smoothed level: a coarse face node takes the frame of the fine face node
// at (or nearest) its place and has the components eliminated that the fine one has (contact normals, pins); a coarse
// top node those of the fine top node at (or nearest) its place. The prolongation is zeroed on
// the fine level's eliminated dofs and the restriction on the coarse level's, so the correction
// never moves a constrained dof.
//
// Every level takes the constraints, the coarsest too (refactored when they change: it is small).
// An unconstrained coarsest level, factored once, costs iterations that grow with the mesh
// (14, 18, 25 CG iterations on faces of 16, 32, 64 cells against 11, 12, 13 at Chebyshev degree 3;
// test_fem_multigrid).
//
// PETSc options (the options database, as for every solver here): -gmg_degree (2),
// -gmg_coarse_nodes (200), -gmg_direct_nodes (8000), -gmg_max_levels (8), -gmg_esteig lo,hi (0.1,1.1),
// -gmg_esteig_steps (10), -gmg_coarse_constraints (true), -gmg_single (false; true: the smoothers
// in float); the coarse solver under the prefix gmg_coarse_.
#include <petscksp.h>

#include <memory>
#include <string>
#include <vector>

#include "lib/fem/graded_mesh.hpp"
#include "lib/fem/matrix_free_framed.hpp"

namespace wr {

struct GmgSettings {
  int degree = 2;  // 3 costs a product more per smoothing for fewer CG iterations: 10 % slower (docs/performance.md)
  double coarse_nodes = 200;
  // The coarsest level is factored up to this many nodes, else given one AMG V-cycle.
  double direct_nodes = 8000;
  int max_levels = 8;
  double esteig_lo = 0.1, esteig_hi = 1.1;
  int estimate_steps = 10;
  // The coarsest level takes the contact constraints too (refactored whenever they change), or
  // only the top's and the pins' (factored once).
  bool coarse_constraints = true;
  // The smoothers' and residuals' products in float (CG's own product stays in double), as
  // deal.II's matrix-free multigrid runs (Kronbichler & Ljungkvist, ACM TOPC 6 (2019)). Off by
  // default: on the thesis scene it saved 17 % of a V-cycle and cost 5-10 % more CG iterations
  // (docs/performance.md).
  bool single = false;
};
// The defaults, overridden by the -gmg_* options given.
GmgSettings gmg_settings_from_options();

class GeometricMultigrid {
 public:
  // `fine` is the block's operator on `fine_mesh` (both outlive this object); the coarser
  // levels are built from `spec`, the fine mesh's spec. Collective on `comm`.
  GeometricMultigrid(const GradedMeshSpec& spec, const GradedMesh& fine_mesh, MatrixFreeFramed& fine, MPI_Comm comm,
                     double young, double poisson, const GmgSettings& settings);
  ~GeometricMultigrid();
  GeometricMultigrid(const GeometricMultigrid&) = delete;
  GeometricMultigrid& operator=(const GeometricMultigrid&) = delete;

  // Takes the fine operator's frames and eliminated rows to every level: call after each
  // eliminate() of `fine` and before the solve. Re-estimates the smoothers' bounds when the
  // frames changed; refactors the coarsest level when its constraints changed. Collective.
  void update();
  // x = one V-cycle applied to b (x distinct from b). Collective.
  void apply(Vec b, Vec x);
  // Makes `pc` a PCSHELL that calls apply().
  void attach(PC pc);

  int levels() const;
  std::vector<long long> level_nodes() const;
  std::size_t memory_bytes() const;  // this rank: matrix-free data, transfers, coarse matrix, vectors
  std::string describe() const;      // "4 levels (1047398, 264145, ... nodes), Chebyshev 3, coarse ..."
  double wall_update() const { return wall_update_; }  // s, summed over update() calls
  // Seconds spent per level in the V-cycles so far ("level 0: 12.3 s (600 products), ...").
  std::string timing() const;

 private:
  struct Level;
  void derive_constraints(std::size_t k);  // level k's frames and eliminated rows from level k - 1's
  void chebyshev(Level& L, Vec b, Vec x, bool zero_guess);
  void estimate_bounds(Level& L);
  void restrict_to(std::size_t k, Vec fine_r, Vec coarse_b);    // k: the fine level
  void prolong_add(std::size_t k, Vec coarse_x, Vec fine_x);   // fine_x += P coarse_x
  void vcycle(std::size_t k, Vec b, Vec x);
  static PetscErrorCode shell_apply(PC pc, Vec b, Vec x);

  MPI_Comm comm_;
  GmgSettings set_;
  std::vector<std::unique_ptr<Level>> levels_;
  double wall_update_ = 0;
  bool coarse_amg_ = false;
};

}  // namespace wr
