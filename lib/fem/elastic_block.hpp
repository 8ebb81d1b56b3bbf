#pragma once
// A linear-elastic block on a rigid obstacle: Q1 hexahedra on a PETSc DMDA (MPI-partitioned),
// graded towards the contact face z = 0, and the frictionless, non-adhesive contact at its
// bottom face solved by a primal-dual active set (semismooth Newton) loop on the full matrix:
// active contact degrees of freedom are eliminated in place, each linear system is solved by
// CG preconditioned with GAMG (block size 3), warm-started from the previous iterate
// (../shared/notes/fem-solver-study.md; deal.II step-41/42).
//
// This first version handles z-aligned contact normals: u_z >= g(x, y) at every bottom node,
// g = obstacle height - its maximum (the block starts touching the highest point). Units: SI,
// forces in N for the given E (Pa).
#include <functional>
#include <string>
#include <vector>

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
  // Obstacle height at (x, y) in m (periodic in the block's extent); empty = flat.
  std::function<double(double, double)> obstacle;
  double ksp_rtol = 1e-10;
  int max_active_set_iterations = 50;
};

struct ContactSolution {
  double fz = 0, fx = 0, fy = 0;  // N, reaction on the top face (fz > 0 in compression)
  std::size_t contact_nodes = 0, face_nodes = 0;
  int active_set_iterations = 0;
  int linear_iterations = 0;
  double max_penetration = 0;     // m, worst violation of u_z >= g
  bool converged = false;
  std::string message;
};

// Builds the mesh and the stiffness matrix once; solve() may then be called for many loads.
class ElasticBlock {
 public:
  explicit ElasticBlock(const BlockSpec& spec);
  ~ElasticBlock();
  ElasticBlock(const ElasticBlock&) = delete;
  ElasticBlock& operator=(const ElasticBlock&) = delete;

  ContactSolution solve(const ContactLoad& load);
  std::size_t nodes() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace wr
