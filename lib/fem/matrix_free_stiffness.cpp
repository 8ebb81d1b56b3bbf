#include "lib/fem/matrix_free_stiffness.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <algorithm>

#include "lib/fem/elastic_block_impl.hpp"

namespace wr {

using petsc::check;

MatrixFreeStiffness::MatrixFreeStiffness(const GradedMesh& g, MPI_Comm comm, double young, double poisson) : comm_(comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (g.ranks() != ranks) throw std::invalid_argument("matrix-free stiffness: the mesh is partitioned for another rank count");
  own_begin_ = g.owned_begin(rank);
  own_end_ = g.owned_end(rank);
  const std::int32_t n_own = own_end_ - own_begin_;
  std::vector<std::array<double, 576>> layer_k;
  for (int e = 0; e < g.layers(); ++e)
    layer_k.push_back(block_detail::brick_stiffness(g.hx(g.layer_level(e)), g.hy(g.layer_level(e)),
                                                    g.planes()[e + 1].z - g.planes()[e].z, young, poisson));
  stencils_ = std::make_unique<NodeStencils>(g, rank, layer_k);
  const std::vector<std::int32_t>& ghost_ids = stencils_->ghost_ids();
  // The scatter of x's owned and ghost dofs into local_.
  std::vector<PetscInt> from;
  from.reserve(3 * (std::size_t(n_own) + ghost_ids.size()));
  for (std::int32_t id = own_begin_; id < own_end_; ++id)
    for (int c = 0; c < 3; ++c) from.push_back(3 * PetscInt(id) + c);
  for (std::int32_t id : ghost_ids)
    for (int c = 0; c < 3; ++c) from.push_back(3 * PetscInt(id) + c);
  Vec global = nullptr;
  check(VecCreateMPI(comm, 3 * n_own, PETSC_DETERMINE, &global), "VecCreateMPI");
  check(VecCreateSeq(PETSC_COMM_SELF, PetscInt(from.size()), &local_), "VecCreateSeq");
  IS is = nullptr;
  check(ISCreateGeneral(PETSC_COMM_SELF, PetscInt(from.size()), from.data(), PETSC_COPY_VALUES, &is), "ISCreateGeneral");
  check(VecScatterCreate(global, is, local_, nullptr, &scatter_), "VecScatterCreate");
  ISDestroy(&is);
  VecDestroy(&global);
  check(VecCreateMPI(comm, 3 * n_own, PETSC_DETERMINE, &work_), "VecCreateMPI");
  check(MatCreateShell(comm, 3 * n_own, 3 * n_own, PETSC_DETERMINE, PETSC_DETERMINE, const_cast<MatrixFreeStiffness*>(this),
                       &shell_),
        "MatCreateShell");
  check(MatShellSetOperation(shell_, MATOP_MULT,
                             reinterpret_cast<void (*)(void)>(&shell_operation<MatrixFreeStiffness, &MatrixFreeStiffness::multiply, Vec, Vec>)),
        "MatShellSetOperation");
  check(MatShellSetOperation(shell_, MATOP_GET_DIAGONAL,
                             reinterpret_cast<void (*)(void)>(&shell_operation<MatrixFreeStiffness, &MatrixFreeStiffness::diagonal, Vec>)),
        "MatShellSetOperation");
  check(MatSetOption(shell_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
}

MatrixFreeStiffness::~MatrixFreeStiffness() {
  MatDestroy(&shell_);
  VecScatterDestroy(&scatter_);
  VecDestroy(&local_);
  VecDestroy(&work_);
}

std::size_t MatrixFreeStiffness::memory_bytes() const {
  PetscInt n = 0;
  VecGetSize(local_, &n);
  return stencils_->memory_bytes() + std::size_t(n) * sizeof(double);
}

void MatrixFreeStiffness::multiply(Vec x, Vec y) const {
  check(VecScatterBegin(scatter_, x, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(scatter_, x, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* xl = nullptr;
  PetscScalar* yo = nullptr;
  check(VecGetArrayRead(local_, &xl), "VecGetArrayRead");
  check(VecGetArray(y, &yo), "VecGetArray");
  stencils_->apply(xl, yo);
  check(VecRestoreArray(y, &yo), "VecRestoreArray");
  check(VecRestoreArrayRead(local_, &xl), "VecRestoreArrayRead");
}

void MatrixFreeStiffness::multiply_framed(Vec x, Vec y, const std::vector<std::int32_t>& face_slot, const std::vector<double>& frames,
                                          const std::vector<double>& blocks, const std::vector<PetscInt>& eliminated,
                                          double unit_diag) const {
  const PetscInt first = 3 * PetscInt(own_begin_);
  check(VecCopy(x, work_), "VecCopy");
  PetscScalar* w = nullptr;
  check(VecGetArray(work_, &w), "VecGetArray");
  for (PetscInt r : eliminated) w[r - first] = 0;  // P x
  rotate_face_dofs(w, own_begin_, own_end_, face_slot, frames, false);  // R P x
  check(VecRestoreArray(work_, &w), "VecRestoreArray");
  multiply(work_, y);
  PetscScalar* yo = nullptr;
  const PetscScalar *wv = nullptr, *xv = nullptr;
  check(VecGetArray(y, &yo), "VecGetArray");
  check(VecGetArrayRead(work_, &wv), "VecGetArrayRead");
  if (!blocks.empty())  // + C R P x on the face nodes
    for (std::int32_t n = own_begin_; n < own_end_; ++n) {
      const std::int32_t s = face_slot[std::size_t(n)];
      if (s < 0) continue;
      const double* c = &blocks[9 * std::size_t(s)];
      const std::size_t o = 3 * std::size_t(n - own_begin_);
      for (int i = 0; i < 3; ++i) yo[o + i] += c[3 * i] * wv[o] + c[3 * i + 1] * wv[o + 1] + c[3 * i + 2] * wv[o + 2];
    }
  check(VecRestoreArrayRead(work_, &wv), "VecRestoreArrayRead");
  rotate_face_dofs(yo, own_begin_, own_end_, face_slot, frames, true);  // R^T (K + C) R P x
  check(VecGetArrayRead(x, &xv), "VecGetArrayRead");
  for (PetscInt r : eliminated) yo[r - first] = unit_diag * xv[r - first];
  check(VecRestoreArrayRead(x, &xv), "VecRestoreArrayRead");
  check(VecRestoreArray(y, &yo), "VecRestoreArray");
}

void MatrixFreeStiffness::diagonal(Vec d) const {
  PetscScalar* dd = nullptr;
  check(VecGetArray(d, &dd), "VecGetArray");
  for (std::int32_t k = 0; k < own_end_ - own_begin_; ++k)
    for (int i = 0; i < 3; ++i) dd[3 * std::size_t(k) + i] = stencils_->self_block(k)[4 * i];
  check(VecRestoreArray(d, &dd), "VecRestoreArray");
}

void MatrixFreeStiffness::face_diagonal_blocks(const std::vector<std::int32_t>& face_slot, std::vector<double>& blocks) const {
  for (std::int32_t k = 0; k < own_end_ - own_begin_; ++k) {
    const std::int32_t s = face_slot[std::size_t(own_begin_ + k)];
    if (s >= 0) std::copy(stencils_->self_block(k), stencils_->self_block(k) + 9, &blocks[9 * std::size_t(s)]);
  }
}

}  // namespace wr
