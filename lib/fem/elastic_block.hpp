#pragma once
// A linear-elastic block on a rigid periodic obstacle: Q1 hexahedra on a PETSc DMDA
// (MPI-partitioned), graded towards the contact face z = 0; frictionless, non-adhesive contact
// at the bottom face.
//
// Each contact solve is the thesis's iterative Signorini problem (sec. 4.2, Algorithm 1):
// at the current configuration every bottom node casts a ray along its (deformed) outward
// normal against the triangulated obstacle; the hit point q and the obstacle normal N there
// give the linearised constraint N . (x + u) >= N . q, i.e. a bound on the displacement
// component along N. Rotating each bottom node's degrees of freedom into the frame of its N
// (Householder, Q e_z = N) turns the constraints into simple bounds; the bound-constrained
// problem is solved by a primal-dual active set (semismooth Newton) loop on the full rotated
// matrix, active degrees of freedom eliminated in place, CG preconditioned by GAMG (block
// size 3), warm-started (../shared/notes/fem-solver-study.md). The correction is damped
// (default 0.8) and the loop stops when the relative change of the bottom-face displacement
// (l2 over the face nodes: the lumped boundary mass on this uniform face grid) is below a
// tolerance. Units: SI, forces in N for the given E (Pa).
#include <string>
#include <vector>

#include "lib/contact/periodic_obstacle.hpp"

namespace wr {

struct BlockSpec {
  double lx = 0.03, ly = 0.03, lz = 0.03;  // m
  int nx = 16, ny = 16, nz = 8;             // elements
  double grading = 1.0;                     // z_k = lz (k / nz)^grading; > 1 refines towards z = 0
  double young = 1.0;                       // E, Pa
  double poisson = 0.45;
};

enum class TopCondition { fixed, frictionless };  // top face: all components prescribed, or only z

struct ContactLoad {
  double uz = 0;  // m, downward displacement of the top face
  double ux = 0;  // m, tangential displacement of the top face (fixed top only)
  TopCondition top = TopCondition::fixed;
  // The obstacle, shifted so that its highest point touches z = 0; nullptr = flat at z = 0.
  const PeriodicObstacle* obstacle = nullptr;
  bool follow_geometry = true;   // Algorithm 1 (rays, rotated normals); false: one solve, u_z >= h
  double damping = 0.8;          // alpha_c
  double tolerance = 1e-5;       // relative change of the contact-face displacement
  int max_outer_iterations = 300;
  double ksp_rtol = 1e-7;
  int max_active_set_iterations = 60;
  bool reuse_preconditioner = true;  // keep one AMG hierarchy per load step (rebuilt if CG slows)
  bool face_maps = false;            // gather the contact-face maps below on rank 0
};

struct ContactSolution {
  double fz = 0, fx = 0, fy = 0;  // N, reaction on the top face (fz > 0 in compression)
  std::size_t contact_nodes = 0, face_nodes = 0;
  double mean_separation = 0;     // m, mean vertical gap between the deformed face and the obstacle
  double max_penetration = 0;     // m, worst depth of a face node below the obstacle
  int outer_iterations = 0;       // Signorini (geometry) iterations
  int active_set_iterations = 0;  // PDAS iterations, summed
  int linear_iterations = 0;      // CG iterations, summed
  bool converged = false;
  std::string message;
  std::vector<double> history;    // relative change of the face displacement per outer iteration
  double final_damping = 0;       // alpha_c at the end (halved while the iteration stagnated)
  // Contact-face maps, (nx+1) x (ny+1) row-major (rows = y), on rank 0 when requested:
  std::vector<double> face_pressure;  // Pa, normal contact force / nodal area
  std::vector<double> face_gap;       // m, vertical gap between the deformed face and the obstacle
  std::vector<double> face_status;    // 1 in contact, 0 free
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
  // The deformed block (displacement field on the graded grid) as a VTK structured grid
  // (.vts, ParaView), written through PETSc's VTK viewer.
  void write_vts(const std::string& path) const;
  std::size_t nodes() const;
  std::size_t dofs() const { return 3 * nodes(); }

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace wr
