#pragma once
// The contact iteration's operator, Khat = R^T (K + C) R in the face nodes' constraint frames,
// with active rows and columns eliminated while a solve runs (sec. 4.2, Algorithm 1, steps 2-3),
// behind one interface with two implementations:
// - FramedStiffness (framed_stiffness.hpp): K assembled as an AIJ matrix, rotated and reduced in
//   place; what AMG and the direct solver need.
// - MatrixFreeFramed (matrix_free_framed.hpp): K never assembled, the frames, face blocks and
//   eliminations applied as vector operations around a matrix-free product; what the geometric
//   multigrid (geometric_multigrid.hpp) smooths with.
// The active-set loop (elastic_block_active_set.cpp) sees only this interface.
//
// Conventions (both): 3 dofs per node, rows by whole nodes; face_slot[node] = the node's face
// index or -1; frames are 9 numbers per face slot, row-major Q with Q e_z = the constraint normal
// (every rank holds all of them); blocks C are symmetric 3 x 3 per face slot in the global frame.
// Every method but the accessors is collective.
#include <petscmat.h>

#include <vector>

namespace wr {

class FramedOperator {
 public:
  virtual ~FramedOperator() = default;
  // Khat (as a PETSc Mat: AIJ or shell), reduced while an elimination is in force.
  virtual Mat mat() const = 0;
  virtual const std::vector<double>& frames() const = 0;
  // Khat <- R_new^T (K + C) R_new. Restores any elimination first.
  virtual void set_frames(const std::vector<double>& frames) = 0;
  // C <- the given blocks (9 per face slot; only the owned slots are read; all zero: K alone).
  // Restores any elimination first.
  virtual void set_face_blocks(const std::vector<double>& blocks) = 0;
  // Zeroes the rows and columns `rows` (global, owned), their diagonal set to unit_diag; b gets
  // f - Khat x_e on the other rows (x_e: x on `rows`, 0 elsewhere; f = 0 when null) and
  // unit_diag x on these (MatZeroRowsColumns's convention), so that the reduced system keeps x's
  // values there. x, b and f are distinct vectors of Khat's layout.
  virtual void eliminate(const std::vector<PetscInt>& rows, double unit_diag, Vec x, Vec b, Vec f) = 0;
  // Undoes eliminate() (no-op without one).
  virtual void restore() = 0;
  // out = (K + C) v in the original frames (v not changed; out distinct from v). Restores any
  // elimination first.
  virtual void multiply_unrotated(Vec v, Vec out) = 0;
  // v <- R^T v (transpose) or R v on the owned face nodes, with the given frames.
  virtual void rotate_vector(Vec v, const std::vector<double>& frames, bool transpose) const = 0;
};

}  // namespace wr
