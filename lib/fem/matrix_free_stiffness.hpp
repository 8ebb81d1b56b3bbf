#pragma once
// The block's stiffness applied without a matrix (issue 58): y = K x with K = sum over the bricks
// of C_e^T K_layer C_e (K_layer the one 24 x 24 trilinear brick matrix of each layer, C_e the
// corners' hanging-node interpolation: lib/fem/local_bricks.hpp's bricks and weights, as the
// assembled matrix). The product runs on K's rows held as a few shared stencils
// (lib/fem/node_stencils.hpp): 243 multiply-adds per node instead of 576 per brick.
//
// Why: the assembled AIJ matrix streams about 81 nonzeros x 3 rows x 12 bytes = 2.9 KB per node
// and product, and its AMG hierarchy as much again beside it; here a product reads the vector and
// a few kilobytes of stencils (Kronbichler & Kormann, Comput. Fluids 63 (2012), for the idea;
// deal.II's step-37).
//
// Parallel: as the assembled matrix, rows by whole nodes in x-slabs (GradedMesh's ownership);
// the x values of the other ranks' nodes that this rank's rows touch come in through one
// VecScatter per product; every rank writes its own rows only, so nothing is sent back.
// Contract: `mesh` outlives this object; x and y are vectors of K's layout (3 dofs per owned
// node, dof = 3 node + c). Collective on `comm`.
#include <petscmat.h>

#include <array>
#include <exception>
#include <memory>
#include <cstdint>
#include <vector>

#include "lib/fem/graded_mesh.hpp"
#include "lib/fem/node_stencils.hpp"

namespace wr {

// A MATSHELL operation (MatMult: V = Vec, Vec; MatGetDiagonal: V = Vec) that calls M on the shell's
// context, a T, turning an exception into a PETSc error.
template <class T, auto M, class... V>
PetscErrorCode shell_operation(Mat A, V... v) {
  void* ctx = nullptr;
  PetscCall(MatShellGetContext(A, &ctx));
  try {
    (static_cast<const T*>(ctx)->*M)(v...);
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
  return 0;
}

class MatrixFreeStiffness {
 public:
  MatrixFreeStiffness(const GradedMesh& mesh, MPI_Comm comm, double young, double poisson);
  ~MatrixFreeStiffness();
  MatrixFreeStiffness(const MatrixFreeStiffness&) = delete;
  MatrixFreeStiffness& operator=(const MatrixFreeStiffness&) = delete;

  // y = K x (x not changed; y distinct from x).
  void multiply(Vec x, Vec y) const;
  // The product in steps, for an operator that changes a few nodes' values of x first
  // (MatrixFreeFramed): begin_ghosts(v) starts bringing in the other ranks' values from v (only
  // v's entries on their edge nodes are read: stencils().edge_nodes()); load_owned(x) takes x's
  // owned values; stencils().set_node() may then overwrite single nodes; end_ghosts() completes
  // the ghosts; product(y) writes y = K x. Collective: begin_ghosts and end_ghosts. single: the
  // product in float (NodeStencils), for the multigrid's smoothers.
  void begin_ghosts(Vec v) const;
  void end_ghosts(Vec v, bool single = false) const;
  void load_owned(Vec x, bool single = false) const;
  void product(Vec y, bool single = false) const;
  // d = diag(K): Jacobi's and Chebyshev's smoothers' only need of the matrix.
  void diagonal(Vec d) const;
  // The 3 x 3 diagonal blocks of K (row-major) of the owned nodes with face_slot[node] >= 0,
  // written at 9 face_slot[node] of `blocks` (sized 9 x face slots; other entries untouched): what
  // the framed operator's diagonal needs, the face nodes' dofs being rotated.
  void face_diagonal_blocks(const std::vector<std::int32_t>& face_slot, std::vector<double>& blocks) const;
  // A MATSHELL of this operator (MatMult, MatGetDiagonal), for KSP; owned by this object.
  Mat mat() const { return shell_; }
  const NodeStencils& stencils() const { return *stencils_; }
  std::size_t memory_bytes() const;  // the stencils, their buffers and the ghosts' values

 private:
  MPI_Comm comm_;
  std::int32_t own_begin_ = 0, own_end_ = 0;
  std::unique_ptr<NodeStencils> stencils_;
  Vec ghosts_ = nullptr;           // the ghosts' dofs of x, sequential
  VecScatter scatter_ = nullptr;   // x -> ghosts_
  Mat shell_ = nullptr;
};

}  // namespace wr
