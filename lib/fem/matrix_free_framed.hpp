#pragma once
// The contact iteration's framed operator without a matrix (framed_operator.hpp): the state the
// assembled FramedStiffness writes into its AIJ values (frames, face blocks, eliminated rows) is
// kept here as lists and applied around MatrixFreeStiffness's product,
//   Khat x = P R^T (K + C) R P x + unit_diag (I - P) x,
// so that the active-set loop runs unchanged on a block whose stiffness was never assembled.
// Why: memory (the AIJ matrix is 2.6 GB at the thesis scene's refine 2; this holds the stencils
// and their buffers, 0.21 GB) and time (a product reads the vector and a few stencils, not 81
// nonzeros per row). R P is applied to x's face and eliminated nodes only, on their way into
// the stencils' layout, so that the product costs no extra pass over the whole vector;
// the geometric multigrid (geometric_multigrid.hpp) smooths with this operator on every level.
//
// Contract: `mesh` outlives this object; face_slot[node] as in framed_operator.hpp. mat() is a
// MATSHELL with MatMult and MatGetDiagonal (the diagonal of Khat as reduced now). Collective.
#include <cstdint>
#include <memory>
#include <vector>

#include "lib/fem/framed_operator.hpp"
#include "lib/fem/matrix_free_stiffness.hpp"

namespace wr {

class MatrixFreeFramed final : public FramedOperator {
 public:
  MatrixFreeFramed(const GradedMesh& mesh, MPI_Comm comm, double young, double poisson, std::vector<std::int32_t> face_slot);
  ~MatrixFreeFramed() override;
  MatrixFreeFramed(const MatrixFreeFramed&) = delete;
  MatrixFreeFramed& operator=(const MatrixFreeFramed&) = delete;

  Mat mat() const override { return shell_; }
  const std::vector<double>& frames() const override { return frames_; }
  void set_frames(const std::vector<double>& frames) override;
  void set_face_blocks(const std::vector<double>& blocks) override;
  void eliminate(const std::vector<PetscInt>& rows, double unit_diag, Vec x, Vec b, Vec f) override;
  void restore() override;
  void multiply_unrotated(Vec v, Vec out) override;
  void rotate_vector(Vec v, const std::vector<double>& frames, bool transpose) const override;

  // The elimination of eliminate() without its right-hand side (a multigrid level's operator).
  void set_eliminated(std::vector<PetscInt> rows, double unit_diag);
  // y = Khat x with the state now in force; d = its diagonal. multiply_with(.., true): K's
  // product in float (the multigrid's smoothers), the framing in double.
  void multiply(Vec x, Vec y) const { multiply_with(x, y, false); }
  void multiply_with(Vec x, Vec y, bool single) const;
  void diagonal(Vec d) const;
  // The eliminated rows now in force (global, owned; empty after restore()) and their diagonal.
  const std::vector<PetscInt>& eliminated() const { return eliminated_; }
  double unit_diag() const { return unit_diag_; }
  // Counts set_frames() and set_face_blocks() calls: a preconditioner's cue to re-estimate what
  // depends on the frames (its smoothers' eigenvalue bounds).
  unsigned long frames_version() const { return frames_version_; }
  const std::vector<std::int32_t>& face_slot() const { return face_slot_; }
  const MatrixFreeStiffness& stiffness() const { return k_; }
  std::int32_t own_begin() const { return own_begin_; }
  std::int32_t own_end() const { return own_end_; }
  std::size_t memory_bytes() const;

 private:
  void bump_state();
  void refresh_mask();                       // mask_ and masked_nodes_ from eliminated_
  void framed_value(std::int32_t k, const PetscScalar* x, double* v) const;  // (R P x) at owned node k


  MatrixFreeStiffness k_;
  std::vector<std::int32_t> face_slot_;
  std::int32_t own_begin_ = 0, own_end_ = 0;
  std::vector<double> frames_, blocks_;  // 9 per face slot; blocks_ empty: no C
  std::vector<double> face_diag_;        // K's 3 x 3 diagonal blocks of the owned face slots
  std::vector<PetscInt> eliminated_;
  std::vector<std::int32_t> face_node_, face_node_slot_;  // the owned face nodes (id - own_begin) and their slots
  std::vector<char> mask_;                  // per owned dof: eliminated
  std::vector<std::int32_t> masked_nodes_;  // owned nodes off the face with an eliminated dof
  mutable std::vector<double> face_value_;  // a product's R P x on the face nodes
  double unit_diag_ = 1;
  unsigned long frames_version_ = 0;
  Vec diag_k_ = nullptr;  // diag(K), computed once
  Vec work_ = nullptr;
  Vec send_ = nullptr;  // R P x on the edge nodes, for the other ranks' ghosts
  Mat shell_ = nullptr;
};

}  // namespace wr
