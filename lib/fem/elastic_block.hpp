#pragma once
// A linear-elastic block on a rigid periodic obstacle: trilinear bricks on a mesh graded
// towards the contact face z = 0 in depth and in-plane (lib/fem/graded_mesh.hpp, hanging
// nodes constrained), assembled into a PETSc matrix partitioned in x-slabs over the MPI ranks;
// frictionless, non-adhesive contact at the bottom face.
//
// Each contact solve is the thesis's iterative Signorini problem (sec. 4.2, Algorithm 1):
// at the current configuration every bottom node casts a ray along its (deformed) outward
// normal against the triangulated obstacle; the hit point q and the obstacle normal N there
// give the linearised constraint N . (x + u) >= N . q, i.e. a bound on the displacement
// component along N. Rotating each bottom node's degrees of freedom into the frame of its N
// (Householder, Q e_z = N) turns the constraints into simple bounds; the bound-constrained
// problem is solved by a primal-dual active set (semismooth Newton) loop on the full rotated
// matrix, active degrees of freedom eliminated in place, CG preconditioned by GAMG (block
// size 3), warm-started (docs/fem-solver.md). The correction is damped
// (default 0.8) and the loop stops when the relative change of the bottom-face displacement
// (l2 over the face nodes: the lumped boundary mass on this uniform face grid) is below a
// tolerance. Units: SI, forces in N for the given E (Pa).
#include <mpi.h>
#include <petscmat.h>

#include <string>
#include <vector>

#include "lib/contact/periodic_obstacle.hpp"
#include "lib/contact/smooth_obstacle.hpp"
#include "lib/fem/amg_hierarchy.hpp"
#include "lib/fem/linear_solver.hpp"
#include "lib/fem/graded_mesh.hpp"

namespace wr {

struct BlockSpec {
  GradedMeshSpec mesh;     // sizes (m), face cells, grading
  double young = 1.0;      // E, Pa
  double poisson = 0.45;
  // The processes that share the block (PETSC_COMM_WORLD by default; PETSC_COMM_SELF lets
  // every rank solve a block of its own, as independent runs of a sweep do).
  MPI_Comm comm = MPI_COMM_NULL;  // null: PETSC_COMM_WORLD
  // CG's AMG hierarchy (amg_hierarchy.hpp); automatic: lean only where the standard one would
  // not fit in this host's memory. PETSc options given by the user (-pc_gamg_agg_nsmooths,
  // -matptap_via) win over either.
  AmgHierarchy amg = AmgHierarchy::automatic;
  // Sparse Cholesky, AMG or the matrix-free multigrid (linear_solver.hpp); automatic: by the
  // block's node count and `use`.
  LinearSolver solver = LinearSolver::automatic;
  LinearSolverUse use;
};

enum class TopCondition { fixed, frictionless };  // top face: all components prescribed, or only z

struct ContactLoad {
  double uz = 0;  // m, downward displacement of the top face
  double ux = 0;  // m, tangential displacement of the top face (fixed top only)
  TopCondition top = TopCondition::fixed;
  // The obstacle, shifted so that its highest point touches z = 0; nullptr = flat at z = 0.
  const PeriodicObstacle* obstacle = nullptr;
  bool follow_geometry = true;   // Algorithm 1 (rays, rotated normals); false: one solve, u_z >= h
  // Set (with follow_geometry): Newton's iteration on this C2 obstacle instead of Algorithm 1 on
  // the triangulated one (the same surface, shifted alike). Each iteration linearises the
  // contact condition z + u_z >= h(x + u_x, y + u_y) at the current face: the bound along
  // N = grad(z - h) / |grad(z - h)| through the point below the node, and, scaled by
  // `curvature`, its second-order term lambda H_h (lambda the node's contact force per unit
  // gradient, H_h the obstacle's Hessian) added to the node's stiffness block: a sequential
  // quadratic programme whose contact set is found by the active-set loop of each iteration, and
  // which converges superlinearly once that set settles. Full steps (no damping, no slow-mode
  // jumps); when CG meets an indefinite system the curvature scale is cut (x 0.25) and the
  // iteration repeated. `obstacle` still names the triangulated surface for the caller's
  // bookkeeping; gaps and penetration are measured on this one.
  const SmoothObstacle* smooth = nullptr;
  double curvature = 1.0;        // scale of the second-order term in [0, 1] (0: Gauss-Newton, linear)
  double damping = 0.8;          // alpha_c
  bool facet_normals = false;     // constraint normal: the hit triangle's (true) or the smooth blend
  double facet_band = 0;          // > 0: facet normals blended into the smooth ones near edges
  // > 0 (experimental): the thesis's reading of sec. 4.2.1, the constraint along the block's own
  // deformed face normal n_k ("as if the node's obstacle was a plane orthogonal to n_k" through
  // the ray's hit), not the obstacle's. Recomputed every Signorini iteration and relaxed: the
  // normal used is N + b (n_k - N), renormalised, b this factor in (0, 1] (1: the thesis's
  // plain update). The force is then along n_k, which a rigid frictionless obstacle cannot
  // exert; this exists to measure what that formulation gives (docs/validation.md).
  double block_normals = 0;
  double tolerance = 1e-5;       // relative change of the contact-face displacement
  // m; > 0: a step that meets the tolerance while a face node is deeper in the obstacle goes on
  // iterating, with tighter loose solves, up to kPenetrationRetries times (the caller's
  // penetration check then judges what is left).
  double max_penetration = 0;
  int max_outer_iterations = 300;
  double ksp_rtol = 1e-7;         // CG tolerance of the final linearisations
  bool inexact = true;            // early linearisations solved loosely (rtol ~ 0.01 x the smallest change so far)
  int max_active_set_iterations = 60;
  // PDAS iterations allowed in a Signorini iteration before the last (the active set then goes
  // on settling across outer iterations; 35 % faster per iteration). Off by default: on a
  // non-convex obstacle it can steer the iteration to another equilibrium (the ratchet test's
  // mirror images then differ by 25 %).
  int early_active_set_iterations = 60;
  bool reuse_preconditioner = true;  // keep one AMG hierarchy per load step (rebuilt if CG slows)
  // Aitken jumps along the slow mode every this many Signorini iterations (0: off;
  // lib/fem/slow_mode_extrapolation.hpp): half the iterations on rough obstacles. Not with
  // facet_normals (a discontinuous map, see elastic_block.cpp).
  int extrapolate_every = 5;
  // With a fixed top, also jump along the face's in-plane rigid modes (FaceModeExtrapolation)
  // every extrapolate_every iterations. Off by default: on the 300 x 300 scene it saved a few
  // of 16 iterations, on the 50 x 50 scene (slide only) it cost 25 % more; not yet measured
  // over a whole Problem A.
  bool face_mode_extrapolation = false;
  bool face_maps = false;            // gather the contact-face maps below on rank 0
  bool trace = false;                // rank 0 prints one line per Signorini iteration (stderr)
  double progress_every_s = 0;       // > 0: rank 0 prints a progress line at most this often (stderr)
};

struct ContactSolution {
  double fz = 0, fx = 0, fy = 0;  // N, reaction on the top face (fz > 0 in compression)
  std::size_t contact_nodes = 0, face_nodes = 0;
  double mean_separation = 0;     // m, mean vertical gap between the deformed face and the obstacle
  double max_penetration = 0;     // m, worst depth of a face node inside the obstacle, perpendicular to the facet above it
  Vec3 deepest_at;                // m, deformed position of that node (when max_penetration > 0)
  std::size_t nodes_over_penetration = 0;  // face nodes deeper than ContactLoad::max_penetration (if > 0)
  int outer_iterations = 0;       // Signorini (geometry) iterations
  int active_set_iterations = 0;  // PDAS iterations, summed
  int linear_iterations = 0;      // CG iterations, summed
  int preconditioner_rebuilds = 0;  // AMG hierarchies rebuilt after a failed solve with a kept one
  int extrapolations = 0;           // slow-mode jumps taken (slow_mode_extrapolation.hpp)
  int curvature_cuts = 0;           // Newton: cuts of the curvature scale after an indefinite system
  int clipped_nodes = 0;            // Newton: face nodes whose negative curvature was bounded, last iteration
  int rejected_jumps = 0;           // of them, undone: the contact set collapsed or the next change grew (jump_overshot)
  bool converged = false;
  std::string message;
  std::vector<double> history;    // relative change of the face displacement per outer iteration
  std::vector<double> mu_history;       // Fx / Fz of each outer iteration's linearised solution
  std::vector<double> damping_history;  // alpha_c applied after each outer iteration
  double final_damping = 0;       // alpha_c at the end (halved while the iteration stagnated)
  double wall_linearise = 0, wall_rotate = 0, wall_solve = 0;  // s, summed over the iterations
  // Contact-face maps, (nx+1) x (ny+1) row-major (rows = y), on rank 0 when requested:
  std::vector<double> face_pressure;  // Pa, normal contact force / nodal area
  std::vector<double> face_gap;       // m, vertical gap between the deformed face and the obstacle
  std::vector<double> face_status;    // 1 in contact, 0 free
};

// What solve() carries from one load step to the next, on this rank: its owned displacement
// dofs (m), its face nodes' contact set and (Newton) contact multipliers. Why: a failed load step is retried from the last
// converged one with a shorter increment (ContactTestOptions::max_cutbacks).
struct BlockState {
  std::vector<double> u;
  std::vector<char> active;
  std::vector<double> lambda;  // Newton: contact multipliers of the face nodes (N per unit gradient)
  double softening_scale = 1;  // Newton: the cut of the curvature's softening part (ElasticBlock::Impl)
};

// Builds the mesh and the stiffness matrix once; solve() may be called for many loads and
// continues from the previous solution (load stepping).
class ElasticBlock {
 public:
  explicit ElasticBlock(const BlockSpec& spec);
  ~ElasticBlock();
  ElasticBlock(const ElasticBlock&) = delete;
  ElasticBlock& operator=(const ElasticBlock&) = delete;

  ContactSolution solve(const ContactLoad& load);
  // The state solve() continues from, and a return to one taken from this block earlier (not
  // collective; every rank restores its own part).
  BlockState state() const;
  // The assembled stiffness in its current frames (the identity until a solve rotates them),
  // for checks of other operators on the same block (matrix_free_stiffness.hpp).
  Mat assembled_stiffness() const;
  MPI_Comm comm() const;
  void restore(const BlockState& s);
  // The deformed block as a VTK unstructured grid (.vtu, ParaView; hexahedra, point data
  // "displacement" in m, hanging nodes interpolated). Collective; rank 0 writes `path`.
  void write_vtu(const std::string& path) const;
  // The contact face's displacement, m: (nx+1) x (ny+1) face nodes, row-major (rows = y), x, y, z
  // per node; on every rank (collective).
  std::vector<double> face_displacement() const;
  // Adds `field`, a displacement given on the (fnx+1) x (fny+1) face lattice of another block
  // over the same face (as face_displacement() returns it), interpolated bilinearly at every
  // node's in-plane position and faded linearly with height to 0 at the top (collective).
  // Why: nested iteration; a coarser block's step increment is a cheap start for this one.
  // Its slow mode (the face creeping along the obstacle) is long-waved, so the coarse mesh
  // resolves it, and the Signorini iteration of the fine mesh is left the short-waved rest.
  void add_lifted_face_field(const std::vector<double>& field, int fnx, int fny);
  std::size_t nodes() const;  // independent nodes
  AmgHierarchy amg_hierarchy() const;  // the one in use: standard or lean, never automatic
  LinearSolver linear_solver() const;  // the one in use: direct, amg or gmg, never automatic
  // The geometric multigrid's levels and smoother (--solver gmg), else empty.
  std::string multigrid_description() const;
  // Its time per level so far and in its updates (--trace), else empty.
  std::string multigrid_timing() const;
  const GradedMesh& mesh() const;
  std::size_t dofs() const { return 3 * nodes(); }

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace wr
