#include "lib/fem/matrix_free_framed.hpp"

#include <stdexcept>

#include "lib/fem/framed_stiffness.hpp"
#include "lib/fem/petsc_session.hpp"

namespace wr {

using petsc::check;

MatrixFreeFramed::MatrixFreeFramed(const GradedMesh& mesh, MPI_Comm comm, double young, double poisson,
                                   std::vector<std::int32_t> face_slot)
    : k_(mesh, comm, young, poisson), face_slot_(std::move(face_slot)) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  own_begin_ = mesh.owned_begin(rank);
  own_end_ = mesh.owned_end(rank);
  std::size_t slots = 0;
  for (std::int32_t s : face_slot_) slots += s >= 0;
  frames_.assign(9 * slots, 0.0);
  for (std::size_t s = 0; s < slots; ++s) frames_[9 * s] = frames_[9 * s + 4] = frames_[9 * s + 8] = 1.0;
  face_diag_.assign(frames_.size(), 0.0);
  k_.face_diagonal_blocks(face_slot_, face_diag_);
  const PetscInt n = 3 * PetscInt(own_end_ - own_begin_);
  check(VecCreateMPI(comm, n, PETSC_DETERMINE, &diag_k_), "VecCreateMPI");
  check(VecDuplicate(diag_k_, &work_), "VecDuplicate");
  k_.diagonal(diag_k_);
  check(MatCreateShell(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, this, &shell_), "MatCreateShell");
  check(MatShellSetOperation(shell_, MATOP_MULT,
                             reinterpret_cast<void (*)(void)>(&shell_operation<MatrixFreeFramed, &MatrixFreeFramed::multiply, Vec, Vec>)),
        "MatShellSetOperation");
  check(MatShellSetOperation(shell_, MATOP_GET_DIAGONAL,
                             reinterpret_cast<void (*)(void)>(&shell_operation<MatrixFreeFramed, &MatrixFreeFramed::diagonal, Vec>)),
        "MatShellSetOperation");
  check(MatSetOption(shell_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
}

MatrixFreeFramed::~MatrixFreeFramed() {
  MatDestroy(&shell_);
  VecDestroy(&diag_k_);
  VecDestroy(&work_);
}

std::size_t MatrixFreeFramed::memory_bytes() const {
  return k_.memory_bytes() + (frames_.size() + blocks_.size() + face_diag_.size()) * sizeof(double) +
         face_slot_.size() * sizeof(std::int32_t) + 2 * 3 * std::size_t(own_end_ - own_begin_) * sizeof(double);
}

void MatrixFreeFramed::set_frames(const std::vector<double>& frames) {
  if (frames.size() != frames_.size()) throw std::invalid_argument("MatrixFreeFramed: 9 frame entries per face node");
  restore();
  frames_ = frames;
  ++frames_version_;
  bump_state();
}

void MatrixFreeFramed::set_face_blocks(const std::vector<double>& blocks) {
  if (blocks.size() != frames_.size()) throw std::invalid_argument("MatrixFreeFramed: 9 block entries per face node");
  restore();
  bool any = false;
  for (double c : blocks) any |= c != 0;
  if (any) blocks_ = blocks;
  else blocks_.clear();
  ++frames_version_;
  bump_state();
}

void MatrixFreeFramed::multiply(Vec x, Vec y) const {
  k_.multiply_framed(x, y, face_slot_, frames_, blocks_, eliminated_, unit_diag_);
}

void MatrixFreeFramed::diagonal(Vec d) const {
  check(VecCopy(diag_k_, d), "VecCopy");
  PetscScalar* a = nullptr;
  check(VecGetArray(d, &a), "VecGetArray");
  for (std::int32_t n = own_begin_; n < own_end_; ++n) {
    const std::int32_t s = face_slot_[std::size_t(n)];
    if (s < 0) continue;
    const std::size_t o = 9 * std::size_t(s);
    double b[9];
    for (int k = 0; k < 9; ++k) b[k] = face_diag_[o + k] + (blocks_.empty() ? 0.0 : blocks_[o + k]);
    const double* q = &frames_[o];
    // (Q^T B Q)_ii = sum_jk Q_ji B_jk Q_ki.
    for (int i = 0; i < 3; ++i) {
      double v = 0;
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) v += q[3 * j + i] * b[3 * j + k] * q[3 * k + i];
      a[3 * std::size_t(n - own_begin_) + i] = v;
    }
  }
  const PetscInt first = 3 * PetscInt(own_begin_);
  for (PetscInt r : eliminated_) a[r - first] = unit_diag_;
  check(VecRestoreArray(d, &a), "VecRestoreArray");
}

void MatrixFreeFramed::eliminate(const std::vector<PetscInt>& rows, double unit_diag, Vec x, Vec b, Vec f) {
  restore();
  const PetscInt first = 3 * PetscInt(own_begin_), n = 3 * PetscInt(own_end_ - own_begin_);
  std::vector<char> mine(std::size_t(n), 0);
  for (PetscInt r : rows) {
    if (r < first || r >= first + n) throw std::invalid_argument("MatrixFreeFramed::eliminate: a row not owned");
    mine[std::size_t(r - first)] = 1;
  }
  {
    const PetscScalar* xa;
    PetscScalar* wa;
    check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
    check(VecGetArray(work_, &wa), "VecGetArray");
    for (PetscInt i = 0; i < n; ++i) wa[i] = mine[std::size_t(i)] ? xa[i] : 0.0;
    check(VecRestoreArray(work_, &wa), "VecRestoreArray");
    check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
  }
  multiply(work_, b);  // Khat x_e, nothing eliminated yet
  PetscScalar* ba;
  const PetscScalar *xa, *fa = nullptr;
  check(VecGetArray(b, &ba), "VecGetArray");
  check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
  if (f) check(VecGetArrayRead(f, &fa), "VecGetArrayRead");
  for (PetscInt i = 0; i < n; ++i) ba[i] = mine[std::size_t(i)] ? unit_diag * xa[i] : (fa ? fa[i] : 0.0) - ba[i];
  if (f) check(VecRestoreArrayRead(f, &fa), "VecRestoreArrayRead");
  check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
  check(VecRestoreArray(b, &ba), "VecRestoreArray");
  eliminated_.clear();
  for (PetscInt i = 0; i < n; ++i)
    if (mine[std::size_t(i)]) eliminated_.push_back(first + i);
  unit_diag_ = unit_diag;
  bump_state();
}

// The operator changed: its state must move so that KSP and a PC see a new operator (an
// assembly is PETSc's public way of saying so for a shell).
void MatrixFreeFramed::bump_state() {
  check(MatAssemblyBegin(shell_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(shell_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

void MatrixFreeFramed::set_eliminated(std::vector<PetscInt> rows, double unit_diag) {
  eliminated_ = std::move(rows);
  unit_diag_ = unit_diag;
  bump_state();
}

void MatrixFreeFramed::restore() {
  if (eliminated_.empty()) return;
  eliminated_.clear();
  bump_state();
}

void MatrixFreeFramed::multiply_unrotated(Vec v, Vec out) {
  restore();
  k_.multiply(v, out);
  if (blocks_.empty()) return;
  const PetscScalar* va;
  PetscScalar* oa;
  check(VecGetArrayRead(v, &va), "VecGetArrayRead");
  check(VecGetArray(out, &oa), "VecGetArray");
  for (std::int32_t n = own_begin_; n < own_end_; ++n) {
    const std::int32_t s = face_slot_[std::size_t(n)];
    if (s < 0) continue;
    const double* c = &blocks_[9 * std::size_t(s)];
    const std::size_t o = 3 * std::size_t(n - own_begin_);
    for (int i = 0; i < 3; ++i) oa[o + i] += c[3 * i] * va[o] + c[3 * i + 1] * va[o + 1] + c[3 * i + 2] * va[o + 2];
  }
  check(VecRestoreArray(out, &oa), "VecRestoreArray");
  check(VecRestoreArrayRead(v, &va), "VecRestoreArrayRead");
}

void MatrixFreeFramed::rotate_vector(Vec v, const std::vector<double>& frames, bool transpose) const {
  rotate_face_dofs(v, own_begin_, own_end_, face_slot_, frames, transpose);
}

}  // namespace wr
