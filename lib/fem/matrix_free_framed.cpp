#include "lib/fem/matrix_free_framed.hpp"

#include <algorithm>
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
  check(VecDuplicate(diag_k_, &send_), "VecDuplicate");
  for (std::int32_t n = own_begin_; n < own_end_; ++n)
    if (face_slot_[std::size_t(n)] >= 0) {
      face_node_.push_back(n - own_begin_);
      face_node_slot_.push_back(face_slot_[std::size_t(n)]);
    }
  mask_.assign(std::size_t(n), 0);
  face_value_.assign(3 * face_node_.size(), 0.0);
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
  VecDestroy(&send_);
}

std::size_t MatrixFreeFramed::memory_bytes() const {
  return k_.memory_bytes() + (frames_.size() + blocks_.size() + face_diag_.size()) * sizeof(double) +
         face_slot_.size() * sizeof(std::int32_t) + 3 * 3 * std::size_t(own_end_ - own_begin_) * sizeof(double) + mask_.size() +
         (face_node_.size() + face_node_slot_.size() + masked_nodes_.size()) * sizeof(std::int32_t) +
         face_value_.size() * sizeof(double);
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

inline void MatrixFreeFramed::framed_value(std::int32_t k, const PetscScalar* x, double* v) const {
  const std::size_t o = 3 * std::size_t(k);
  double w[3];
  for (int c = 0; c < 3; ++c) w[c] = mask_[o + std::size_t(c)] ? 0.0 : x[o + std::size_t(c)];
  const std::int32_t s = face_slot_[std::size_t(own_begin_ + k)];
  if (s < 0) {
    std::copy(w, w + 3, v);
    return;
  }
  rotate_node(&frames_[9 * std::size_t(s)], w, v, false);
}

// Khat x = P R^T (K + C) R P x + unit_diag (I - P) x: R P x differs from x only on the face nodes
// and the eliminated dofs, so x goes into the stencils as it is and those nodes are overwritten.
void MatrixFreeFramed::multiply_with(Vec x, Vec y, bool single) const {
  const NodeStencils& st = k_.stencils();
  const PetscScalar* xa = nullptr;
  check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
  if (!st.edge_nodes().empty()) {
    PetscScalar* sa = nullptr;
    check(VecGetArray(send_, &sa), "VecGetArray");
    for (std::int32_t k : st.edge_nodes()) framed_value(k, xa, sa + 3 * std::size_t(k));
    check(VecRestoreArray(send_, &sa), "VecRestoreArray");
  }
  k_.begin_ghosts(send_);
  st.load_owned(xa, single);
  double* fv = face_value_.data();  // R P x on the face nodes, kept for C below
  for (std::size_t f = 0; f < face_node_.size(); ++f) {
    framed_value(face_node_[f], xa, fv + 3 * f);
    st.set_node(face_node_[f], fv + 3 * f, single);
  }
  double v[3];
  for (std::int32_t k : masked_nodes_) {
    framed_value(k, xa, v);
    st.set_node(k, v, single);
  }
  k_.end_ghosts(send_, single);
  PetscScalar* ya = nullptr;
  check(VecGetArray(y, &ya), "VecGetArray");
  st.product(ya, single);
  for (std::size_t f = 0; f < face_node_.size(); ++f) {  // + C R P x, then R^T
    const std::size_t s9 = 9 * std::size_t(face_node_slot_[f]);
    double* yk = ya + 3 * std::size_t(face_node_[f]);
    if (!blocks_.empty()) add_node_block(&blocks_[s9], fv + 3 * f, yk);
    rotate_node(&frames_[s9], yk, yk, true);
  }
  const PetscInt first = 3 * PetscInt(own_begin_);
  for (PetscInt r : eliminated_) ya[r - first] = unit_diag_ * xa[r - first];
  check(VecRestoreArray(y, &ya), "VecRestoreArray");
  check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
}

void MatrixFreeFramed::refresh_mask() {
  std::fill(mask_.begin(), mask_.end(), 0);
  masked_nodes_.clear();
  const PetscInt first = 3 * PetscInt(own_begin_);
  for (PetscInt r : eliminated_) {
    const std::size_t d = std::size_t(r - first);
    if (d >= mask_.size()) throw std::invalid_argument("MatrixFreeFramed: an eliminated row not owned");
    mask_[d] = 1;
  }
  for (std::size_t k = 0; 3 * k < mask_.size(); ++k)
    if ((mask_[3 * k] || mask_[3 * k + 1] || mask_[3 * k + 2]) && face_slot_[std::size_t(own_begin_) + k] < 0)
      masked_nodes_.push_back(std::int32_t(k));
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
  refresh_mask();
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
  refresh_mask();
  bump_state();
}

void MatrixFreeFramed::restore() {
  if (eliminated_.empty()) return;
  eliminated_.clear();
  refresh_mask();
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
    const std::size_t o = 3 * std::size_t(n - own_begin_);
    add_node_block(&blocks_[9 * std::size_t(s)], va + o, oa + o);
  }
  check(VecRestoreArray(out, &oa), "VecRestoreArray");
  check(VecRestoreArrayRead(v, &va), "VecRestoreArrayRead");
}

void MatrixFreeFramed::rotate_vector(Vec v, const std::vector<double>& frames, bool transpose) const {
  rotate_face_dofs(v, own_begin_, own_end_, face_slot_, frames, transpose);
}

}  // namespace wr
