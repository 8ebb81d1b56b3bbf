#pragma once
// The private part of ElasticBlock (lib/fem/elastic_block.hpp), shared by the files of its
// phases: elastic_block_assembly.cpp (mesh and stiffness), elastic_block.cpp (life, state,
// fields, VTU), elastic_block_linearise.cpp (the top's boundary, the linearisation and the
// rotation into constraint frames), elastic_block_active_set.cpp (active-set solve, correction,
// gaps, forces, results, face modes), elastic_block_solve.cpp (the Signorini iteration).
// Not for use outside lib/fem.

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <utility>

#include "lib/contact/adaptive_damping.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/fem/framed_stiffness.hpp"
#include "lib/fem/geometric_multigrid.hpp"
#include "lib/fem/matrix_free_framed.hpp"
#include "lib/fem/local_bricks.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/fem/penetration_retries.hpp"
#include "lib/fem/slow_mode_extrapolation.hpp"
#include "lib/io/vtu_writer.hpp"

#include "lib/fem/elastic_block.hpp"

namespace wr {
namespace block_detail {

// A solver default that a user's -option (command line, --petsc) overrides.
void set_default_option(const char* name, const char* value);

// A solver default that lives as long as this object and is removed after it, unless the user
// gave it. Why scoped: PETSc's options database is process-wide, and a process may hold blocks
// of both hierarchies (tests, nested iteration, the mesh-convergence bench).
class ScopedDefaultOption {
 public:
  ScopedDefaultOption(const char* name, const char* value) : name_(name) {
    PetscBool given = PETSC_FALSE;
    PetscOptionsHasName(nullptr, nullptr, name, &given);
    if (!given) set_ = PetscOptionsSetValue(nullptr, name, value) == 0;
  }
  ~ScopedDefaultOption() {
    if (set_) PetscOptionsClearValue(nullptr, name_);
  }
  ScopedDefaultOption(const ScopedDefaultOption&) = delete;
  ScopedDefaultOption& operator=(const ScopedDefaultOption&) = delete;

 private:
  const char* name_;
  bool set_ = false;
};


// The nodes owned by the ranks of `comm` that share this host (the ranks split the nodes about
// equally: x-slabs with equal shares of the face).
double nodes_on_this_host(MPI_Comm comm, double nodes);

// CG's default test, or with a least reduction of the solve's own initial residual (> 0):
// elastic_block_assembly.cpp says why.
void set_convergence_test(KSP ksp, double least_reduction);

using ElementMatrix = std::array<double, 24 * 24>;
// The block's stiffness K = sum_e C_e^T K_e C_e over the bricks of `g` (hanging-node
// interpolation C_e), as an AIJ matrix with 3 x 3 node blocks, rows of the nodes each rank of
// `comm` owns; exact preallocation, and every rank assembles its own rows from the bricks around
// them, so no entries travel between ranks. Collective.
Mat assemble_stiffness(const GradedMesh& g, MPI_Comm comm, double young, double poisson);
// Stiffness of an axis-aligned Q1 brick (hx, hy, hz), 2x2x2 Gauss (exact for the brick).
// Local node a = ia + 2 ja + 4 ka, dof a*3 + c.
ElementMatrix brick_stiffness(double hx, double hy, double hz, double E, double nu);

struct FaceNode {
  std::int32_t i, j;
  PetscInt row[3];  // global dofs
  Vec3 x0;          // reference position
  Vec3 normal{0, 0, 1};  // obstacle normal N of the current linearisation
  double g = -INFINITY;  // bound on N . u (-inf: no obstacle within reach)
  double hxx = 0, hxy = 0, hyy = 0;  // Newton: the smooth obstacle's Hessian below the node, 1/m
};

// The contact face's in-plane rigid modes (FaceModeExtrapolation): slide x, slide y,
// dilatation and twist about the face centre, the last two scaled by the face's rms radius so
// that every coordinate is a displacement (m). They are orthogonal on the face lattice, so each
// coordinate is a projection.
struct FaceModeBasis {
  double xc, yc, radius = 1;  // m; the radius only computed when `on`
  FaceModeBasis(const GradedMesh& g, double lx, double ly, int fnx, int fny, bool on) : xc(0.5 * lx), yc(0.5 * ly) {
    if (!on) return;
    double sum = 0;
    for (int j = 0; j <= fny; ++j)
      for (int i = 0; i <= fnx; ++i) {
        const Vec3 p = g.position(0, i, j);
        sum += (p.x - xc) * (p.x - xc) + (p.y - yc) * (p.y - yc);
      }
    radius = std::sqrt(sum / double((fnx + 1) * (fny + 1)));
  }
  // In-plane shape {x, y} of mode k at (x, y).
  std::array<double, 2> shape(double x, double y, int k) const {
    const double rx = (x - xc) / radius, ry = (y - yc) / radius;
    switch (k) {
      case 0: return {1, 0};
      case 1: return {0, 1};
      case 2: return {rx, ry};
      default: return {-ry, rx};
    }
  }
};

// Householder reflection with Q e_z = n (symmetric, orthogonal), row-major.
std::array<double, 9> frame_of(const Vec3& n);

}  // namespace block_detail

using namespace block_detail;

struct ElasticBlock::Impl {
  BlockSpec spec;
  MPI_Comm comm = MPI_COMM_NULL;
  AmgHierarchy amg = AmgHierarchy::standard;  // spec.amg resolved for this mesh and host
  LinearSolver solver = LinearSolver::amg;     // spec.solver resolved for this mesh
  std::unique_ptr<GradedMesh> mesh;
  int rank = 0;
  PetscInt own_begin = 0, own_end = 0;  // owned node ids
  // Khat = R^T K R in the face nodes' current constraint frames, reduced by the active-set
  // solves: assembled and reduced in place (FramedStiffness; K itself is not kept) or, under
  // the geometric multigrid, without a matrix (MatrixFreeFramed).
  std::unique_ptr<FramedOperator> stiffness;
  std::unique_ptr<GeometricMultigrid> gmg;  // --solver gmg: CG's preconditioner
  MatrixFreeFramed* matrix_free = nullptr;  // stiffness, when it is the matrix-free one
  Vec u = nullptr;  // current displacement, carried from load step to load step
  // The whole contact face, gathered on every rank (normals need the neighbours' positions).
  VecScatter face_scatter = nullptr;
  Vec face_u = nullptr;
  std::vector<char> active;  // per owned face node, carried between solves
  // Newton: per owned face node, its contact force per unit constraint gradient (N) from the
  // last active-set solve, carried between solves: the weight of its curvature term.
  std::vector<double> lambda;
  // Newton: scale of the softening part of the curvature term, cut after an indefinite system
  // and kept so, for the rest of the solve and the next solves (see solve()).
  double softening_scale = 1;
  std::vector<double> face_stiffness;  // Newton: K's mean diagonal entry per owned face node, N/m
  std::vector<std::int32_t> face_slot;  // per node id: its face index j (nx+1) + i, or -1

  PetscInt dof(std::int32_t node, int c) const { return 3 * PetscInt(node) + c; }
  bool owns(std::int32_t node) const { return node >= own_begin && node < own_end; }
  int face_nx() const { return spec.mesh.nx; }
  int face_ny() const { return spec.mesh.ny; }

  // Calls f(layer, ids, weights) for every brick that touches an owned node: ids = the distinct
  // independent nodes behind the 8 corners, weights = 8 x ids.size() (row-major) interpolation.
  template <class F>
  void for_each_local_brick(F&& f) const {
    wr::for_each_local_brick(*mesh, rank, std::int32_t(own_begin), std::int32_t(own_end), std::forward<F>(f));
  }

  void make_grid();
  // The stiffness operator (assembled, or matrix-free with its multigrid), u and the face's scatter.
  void assemble();

  void gather_face() const {
    petsc::check(VecScatterBegin(face_scatter, u, face_u, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    petsc::check(VecScatterEnd(face_scatter, u, face_u, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  }

  // ---- The phases of one solve() (Algorithm 1), defined below it ----
  // The prescribed top dofs (and, under a frictionless top, the minimal pins of two face
  // corners), and the rows whose reactions are the top's forces.
  struct TopBoundary {
    std::vector<PetscInt> fixed_rows;
    std::vector<double> fixed_vals;
    std::vector<PetscInt> top_rows[3];
  };
  // The working set of a solve: vectors in the rotated frames, and CG preconditioned by GAMG
  // (the operator is `stiffness`).
  struct LinearSystems {
    Vec uh = nullptr, b = nullptr, r = nullptr, diag = nullptr, ustar = nullptr;
    // Newton: R^T C u at the linearisation point (C the curvature blocks): the load that makes
    // the quadratic model's minimiser the Newton step; null without curvature.
    Vec shift = nullptr;
    KSP ksp = nullptr;
    Vec before_jump = nullptr;  // the iterate before the last slow-mode jump
    std::vector<double> q_all, q_mine;  // constraint frames, 9 per face slot (all face nodes)
    int first_its = -1;                 // CG iterations with a fresh preconditioner
    // Lean hierarchy: PtAP all at once (no symbolic scratch), for as long as these systems live.
    std::unique_ptr<ScopedDefaultOption> ptap_option;
    LinearSystems(MPI_Comm comm, Vec like, std::size_t face_nodes, AmgHierarchy amg, LinearSolver solver,
                  GeometricMultigrid* gmg);
    ~LinearSystems();
    LinearSystems(const LinearSystems&) = delete;
    LinearSystems& operator=(const LinearSystems&) = delete;
  };
  struct ActiveSetControl {
    double unit_diag = 1;           // diagonal of eliminated rows
    bool loose = false;             // a loose solve: its first system cuts the residual tenfold
    bool accept_unsettled = false;  // an early linearisation may end with the set still moving
    int max_iterations = 1;
    bool reuse_preconditioner = true;
  };
  struct ActiveSetOutcome {
    bool ok = false, settled = false;  // usable; active set unchanged by the last solve
    std::size_t contact = 0;           // this rank's active face nodes
  };
  struct Correction {
    double change = 0;    // |u* - u| / |u*| on the face
    double cosine = NAN;  // with the previous correction (NaN: none)
  };

  std::vector<FaceNode> owned_face_nodes() const;
  // Writes the top's prescribed values into u.
  TopBoundary prescribe_top(const ContactLoad& load);
  // Step 1: normal and gap bound of each face node at the current configuration, by a ray cast
  // along the deformed face's normal (thesis Fig. 4.6).
  void linearise(std::vector<FaceNode>& face, const ContactLoad& load) const;
  // Step 2: Khat = R^T K R and uh = R^T u in the nodes' constraint frames; returns the
  // diagonal scale for eliminated rows. Newton (curvature.on): K + C, C the nodes' curvature
  // blocks (curvature_block in the .cpp), and s.shift = R^T C u; returns through `clipped` how
  // many owned nodes had their negative curvature bounded.
  struct CurvatureScales {
    bool on = false;        // Newton: blocks are set (all zero when `all` is 0)
    double all = 1;         // ContactLoad::curvature
    double negative = 1;    // of the softening part, cut after an indefinite system
  };
  double rotate_into_frames(const std::vector<FaceNode>& face, LinearSystems& s, const CurvatureScales& curvature,
                            int& clipped);
  // Newton, --trace, at a converged state: whether the system with the whole curvature term
  // (the step's scales `full` with the softening one raised to 1, still floored per node) is definite on the free dofs, i.e. on the
  // tangent space of the contact set: the second-order condition Newton's fast local rate rests
  // on (where it fails, the state is held only by nodes at zero gap and zero force); and
  // the curvature the contact forces give the face's rigid slide along x and y
  // (sum of lambda h_xx, lambda h_yy over the contact nodes, N/m) against the block's shear
  // stiffness G Lx Ly / Lz. Overwrites the linear systems; the caller has its result already.
  void print_second_order_check(std::vector<FaceNode>& face, const TopBoundary& top, LinearSystems& s,
                                const ContactLoad& load, CurvatureScales full);
  // The obstacle in use at (x, y): its height and the vertical component of its unit normal.
  struct SurfacePoint {
    double h = 0, nz = 1;
  };
  static SurfacePoint surface_at(const ContactLoad& load, double x, double y);
  // Step 3: primal-dual active set on the bounds uh_z >= g; the solution is left in s.uh, the
  // rotated reactions in s.r, the contact set in `active`. Counts and failures go into `out`.
  ActiveSetOutcome solve_active_set(const std::vector<FaceNode>& face, const TopBoundary& top, LinearSystems& s,
                                    const ActiveSetControl& control, ContactSolution& out);
  // Step 4: the correction u* - u on the face; prev_corr (3 per face node) becomes this one.
  Correction measure_correction(const std::vector<FaceNode>& face, Vec ustar, std::vector<double>& prev_corr) const;
  // Vertical gaps of this rank's face nodes for the displacement array a (m): their summed
  // separation, the deepest penetration, where that node is, and how many nodes are deeper
  // than load.max_penetration.
  struct FaceGaps {
    double separation = 0, deepest = 0;
    Vec3 deepest_at;
    std::size_t over_limit = 0;
  };
  FaceGaps face_gaps(const std::vector<FaceNode>& face, const PetscScalar* a, const ContactLoad& load) const;
  double deepest_penetration(const std::vector<FaceNode>& face, Vec v, const ContactLoad& load) const;  // collective
  // {Fx, Fy, Fz} on the top face for displacement v (Fz > 0 in compression); `work` is
  // overwritten. Collective.
  std::array<double, 3> top_forces(Vec v, const TopBoundary& top, Vec work) const;
  FaceModeExtrapolation::Modes face_mode_coordinates(const std::vector<FaceNode>& face,
                                                     const FaceModeBasis& basis) const;
  // Adds the modal displacement c through the block, fading linearly to the fixed top.
  void add_face_modes(const FaceModeBasis& basis, const FaceModeExtrapolation::Modes& c);
  // Calls f(x, w, d) for every owned independent node: x its reference position, w = 1 - its
  // height / lz (1 on the face, 0 on the fixed top), d its three entries of u. Shared by the
  // ways of spreading a face displacement through the block (face modes, the coarse start).
  template <class F>
  void for_each_lifted_node(F&& f) {
    const GradedMesh& g = *mesh;
    const PetscInt rstart = 3 * PetscInt(own_begin);
    const auto& planes = g.planes();
    const double z0 = planes.front().z, lz = planes.back().z - z0;
    PetscScalar* a;
    VecGetArray(u, &a);
    for (std::size_t p = 0; p < planes.size(); ++p) {
      const double w = 1 - (planes[p].z - z0) / lz;
      const int nxp = g.cells_x(planes[p].level), nyp = g.cells_y(planes[p].level);
      for (int j = 0; j <= nyp; ++j)
        for (int i = 0; i <= nxp; ++i) {
          const std::int32_t id = planes[p].id[std::size_t(j) * (nxp + 1) + i];
          if (id < 0 || !owns(id)) continue;
          f(g.position(int(p), i, j), w, a + (dof(id, 0) - rstart));
        }
    }
    VecRestoreArray(u, &a);
  }
  // Reactions, separation, penetration and (if asked) the face maps of the final u.
  void output_results(const std::vector<FaceNode>& face, const TopBoundary& top,
                      const std::vector<double>& normal_force, const ContactLoad& load, Vec work,
                      ContactSolution& out) const;
};

}  // namespace wr
