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
  // The scatter of the ghosts' dofs into ghosts_.
  std::vector<PetscInt> from;
  from.reserve(3 * ghost_ids.size());
  for (std::int32_t id : ghost_ids)
    for (int c = 0; c < 3; ++c) from.push_back(3 * PetscInt(id) + c);
  Vec global = nullptr;
  check(VecCreateMPI(comm, 3 * n_own, PETSC_DETERMINE, &global), "VecCreateMPI");
  check(VecCreateSeq(PETSC_COMM_SELF, PetscInt(from.size()), &ghosts_), "VecCreateSeq");
  IS is = nullptr;
  check(ISCreateGeneral(PETSC_COMM_SELF, PetscInt(from.size()), from.data(), PETSC_COPY_VALUES, &is), "ISCreateGeneral");
  check(VecScatterCreate(global, is, ghosts_, nullptr, &scatter_), "VecScatterCreate");
  ISDestroy(&is);
  VecDestroy(&global);
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
  VecDestroy(&ghosts_);
}

std::size_t MatrixFreeStiffness::memory_bytes() const {
  PetscInt n = 0;
  VecGetSize(ghosts_, &n);
  return stencils_->memory_bytes() + std::size_t(n) * sizeof(double);
}

void MatrixFreeStiffness::begin_ghosts(Vec v) const {
  check(VecScatterBegin(scatter_, v, ghosts_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
}

void MatrixFreeStiffness::end_ghosts(Vec v, bool single) const {
  check(VecScatterEnd(scatter_, v, ghosts_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* g = nullptr;
  check(VecGetArrayRead(ghosts_, &g), "VecGetArrayRead");
  stencils_->load_ghosts(g, single);
  check(VecRestoreArrayRead(ghosts_, &g), "VecRestoreArrayRead");
}

void MatrixFreeStiffness::load_owned(Vec x, bool single) const {
  const PetscScalar* xa = nullptr;
  check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
  stencils_->load_owned(xa, single);
  check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
}

void MatrixFreeStiffness::product(Vec y, bool single) const {
  PetscScalar* ya = nullptr;
  check(VecGetArray(y, &ya), "VecGetArray");
  stencils_->product(ya, single);
  check(VecRestoreArray(y, &ya), "VecRestoreArray");
}

void MatrixFreeStiffness::multiply(Vec x, Vec y) const {
  begin_ghosts(x);
  load_owned(x);  // while the ghosts travel
  end_ghosts(x);
  product(y);
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
