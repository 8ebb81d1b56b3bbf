#include "lib/fem/framed_stiffness.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "lib/fem/petsc_session.hpp"

namespace wr {
namespace {

using petsc::check;

using Block = std::array<double, 9>;  // row-major 3 x 3

// D = Qa^T Qb for row-major frames.
Block transpose_times(const double* qa, const double* qb) {
  Block d{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d[3 * i + j] = qa[i] * qb[j] + qa[3 + i] * qb[3 + j] + qa[6 + i] * qb[6 + j];
  return d;
}

bool is_identity(const Block& d) {
  static const Block eye{1, 0, 0, 0, 1, 0, 0, 0, 1};
  return d == eye;
}

}  // namespace

FramedStiffness::FramedStiffness(Mat K, PetscInt own_begin, PetscInt own_end, std::vector<std::int32_t> face_slot)
    : k_(K), own_begin_(own_begin), own_end_(own_end), face_slot_(std::move(face_slot)) {
  try {
    map_structure();
  } catch (...) {
    MatDestroy(&k_);  // owned from the start, also when it is refused
    throw;
  }
}

void FramedStiffness::map_structure() {
  face_slots_ = std::size_t(std::count_if(face_slot_.begin(), face_slot_.end(), [](std::int32_t s) { return s >= 0; }));
  frames_.assign(9 * face_slots_, 0.0);
  for (std::size_t s = 0; s < face_slots_; ++s) frames_[9 * s] = frames_[9 * s + 4] = frames_[9 * s + 8] = 1.0;
  PetscBool mpi = PETSC_FALSE;
  check(PetscObjectTypeCompare(PetscObject(k_), MATMPIAIJ, &mpi), "PetscObjectTypeCompare");
  if (mpi) {
    check(MatMPIAIJGetSeqAIJ(k_, &parts_[0].m, &parts_[1].m, &garray_), "MatMPIAIJGetSeqAIJ");
    n_parts_ = 2;
  } else {
    PetscBool seq = PETSC_FALSE;
    check(PetscObjectTypeCompare(PetscObject(k_), MATSEQAIJ, &seq), "PetscObjectTypeCompare");
    if (!seq) throw std::runtime_error("FramedStiffness: the stiffness must be an AIJ matrix");
    parts_[0].m = k_;
  }
  const PetscInt rows = 3 * (own_end_ - own_begin_);
  for (int p = 0; p < n_parts_; ++p) {
    PetscInt n = 0;
    PetscBool done = PETSC_FALSE;
    check(MatGetRowIJ(parts_[p].m, 0, PETSC_FALSE, PETSC_FALSE, &n, &parts_[p].ia, &parts_[p].ja, &done),
          "MatGetRowIJ");
    if (!done || n != rows) throw std::runtime_error("FramedStiffness: no row structure of the stiffness");
  }
  // The node-block structure every edit below relies on.
  for (PetscInt a = 0; a < own_end_ - own_begin_; ++a)
    for (int p = 0; p < n_parts_; ++p) {
      const Part& q = parts_[p];
      const PetscInt len = q.ia[3 * a + 1] - q.ia[3 * a];
      bool ok = len % 3 == 0;
      for (int r = 1; r < 3 && ok; ++r) ok = q.ia[3 * a + r + 1] - q.ia[3 * a + r] == len;
      for (PetscInt k = 0; k < len && ok; k += 3) {
        const PetscInt c = global_column(q, q.ja[q.ia[3 * a] + k]);
        ok = c % 3 == 0;
        for (int r = 0; r < 3 && ok; ++r)
          for (int j = 0; j < 3 && ok; ++j) ok = global_column(q, q.ja[q.ia[3 * a + r] + k + j]) == c + j;
      }
      if (!ok) throw std::runtime_error("FramedStiffness: the stiffness is not made of 3 x 3 node blocks");
    }
}

FramedStiffness::~FramedStiffness() {
  for (int p = 0; p < n_parts_; ++p) {
    PetscInt n;
    PetscBool done;
    MatRestoreRowIJ(parts_[p].m, 0, PETSC_FALSE, PETSC_FALSE, &n, &parts_[p].ia, &parts_[p].ja, &done);
  }
  if (work_) VecDestroy(&work_);
  MatDestroy(&k_);
}

PetscInt FramedStiffness::global_column(const Part& p, PetscInt j) const {
  return &p == &parts_[0] ? 3 * own_begin_ + j : garray_[j];
}

template <class F>
void FramedStiffness::edit_values(F&& f) {
  for (int p = 0; p < n_parts_; ++p) {
    PetscScalar* v;
    check(MatSeqAIJGetArray(parts_[p].m, &v), "MatSeqAIJGetArray");
    f(p, v);
    check(MatSeqAIJRestoreArray(parts_[p].m, &v), "MatSeqAIJRestoreArray");
  }
  // The parts' states moved; the parallel operator's must too, so that preconditioners see the
  // change: an assembly with nothing stashed only does that (no new entries are allowed).
  if (n_parts_ == 2) {
    check(MatAssemblyBegin(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
}

void FramedStiffness::set_frames(const std::vector<double>& frames) {
  if (frames.size() != frames_.size()) throw std::invalid_argument("FramedStiffness: 9 frame entries per face node");
  restore();
  std::vector<Block> d(face_slots_);
  std::vector<char> moved(face_slots_);
  bool any = false;
  for (std::size_t s = 0; s < face_slots_; ++s) {
    d[s] = transpose_times(&frames_[9 * s], &frames[9 * s]);
    moved[s] = !is_identity(d[s]);
    any |= bool(moved[s]);
  }
  if (any) {
    auto d_of = [&](PetscInt global_col) -> const Block* {
      const std::int32_t s = face_slot_[std::size_t(global_col / 3)];
      return s >= 0 && moved[std::size_t(s)] ? &d[std::size_t(s)] : nullptr;
    };
    edit_values([&](int p, PetscScalar* v) {
      const Part& q = parts_[p];
      for (PetscInt a = 0; a < own_end_ - own_begin_; ++a) {
        const Block* da = d_of(3 * (own_begin_ + a));
        const PetscInt r0 = q.ia[3 * a], len = q.ia[3 * a + 1] - r0;
        const PetscInt r1 = q.ia[3 * a + 1], r2 = q.ia[3 * a + 2];
        for (PetscInt k = 0; k < len; k += 3) {
          const Block* db = d_of(global_column(q, q.ja[r0 + k]));
          if (!da && !db) continue;
          PetscScalar* row[3] = {v + r0 + k, v + r1 + k, v + r2 + k};
          double b[9], t[9];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) b[3 * i + j] = row[i][j];
          // t = Da^T B, then t Db: the block (a, b) of D^T Khat D.
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              t[3 * i + j] = da ? (*da)[i] * b[j] + (*da)[3 + i] * b[3 + j] + (*da)[6 + i] * b[6 + j] : b[3 * i + j];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              row[i][j] = db ? t[3 * i] * (*db)[j] + t[3 * i + 1] * (*db)[3 + j] + t[3 * i + 2] * (*db)[6 + j]
                             : t[3 * i + j];
        }
      }
    });
  }
  frames_ = frames;
}

void FramedStiffness::set_face_blocks(const std::vector<double>& blocks) {
  if (blocks.size() != frames_.size()) throw std::invalid_argument("FramedStiffness: 9 block entries per face node");
  restore();
  if (face_blocks_.empty()) face_blocks_.assign(frames_.size(), 0.0);
  edit_values([&](int p, PetscScalar* v) {
    if (p != 0) return;  // diagonal blocks live in the diagonal part
    const Part& q = parts_[0];
    for (PetscInt a = 0; a < own_end_ - own_begin_; ++a) {
      const std::int32_t s = face_slot_[std::size_t(own_begin_ + a)];
      if (s < 0) continue;
      const std::size_t o = 9 * std::size_t(s);
      Block d;
      bool any = false;
      for (int k = 0; k < 9; ++k) any |= (d[k] = blocks[o + k] - face_blocks_[o + k]) != 0;
      if (!any) continue;
      // Q^T d Q, the change in this node's frame (d symmetric, so d Q = d^T Q).
      const double* qm = &frames_[o];
      const Block r = transpose_times(qm, transpose_times(d.data(), qm).data());
      const PetscInt r0 = q.ia[3 * a], len = q.ia[3 * a + 1] - r0;
      PetscInt k = 0;
      while (k < len && q.ja[r0 + k] != 3 * a) k += 3;
      if (k >= len) throw std::runtime_error("FramedStiffness: a face node without its diagonal block");
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) v[q.ia[3 * a + i] + k + j] += r[3 * i + j];
    }
  });
  face_blocks_ = blocks;
}

void FramedStiffness::eliminate(const std::vector<PetscInt>& rows, double unit_diag, Vec x, Vec b, Vec f) {
  restore();
  const PetscInt r0 = 3 * own_begin_, nrows = 3 * (own_end_ - own_begin_);
  std::vector<char> local(std::size_t(nrows), 0);
  for (PetscInt r : rows) {
    if (r < r0 || r >= r0 + nrows) throw std::invalid_argument("FramedStiffness::eliminate: a row not owned");
    local[std::size_t(r - r0)] = 1;
  }
  // b = -Khat x_e on the other rows (x_e: x on the eliminated rows, 0 elsewhere), before zeroing.
  if (!work_) check(MatCreateVecs(k_, &work_, nullptr), "MatCreateVecs");
  {
    const PetscScalar* xa;
    PetscScalar* wa;
    check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
    check(VecGetArray(work_, &wa), "VecGetArray");
    for (PetscInt i = 0; i < nrows; ++i) wa[i] = local[std::size_t(i)] ? xa[i] : 0.0;
    check(VecRestoreArray(work_, &wa), "VecRestoreArray");
    check(MatMult(k_, work_, b), "MatMult");
    PetscScalar* ba;
    const PetscScalar* fa = nullptr;
    check(VecGetArray(b, &ba), "VecGetArray");
    if (f) check(VecGetArrayRead(f, &fa), "VecGetArrayRead");
    for (PetscInt i = 0; i < nrows; ++i)
      ba[i] = local[std::size_t(i)] ? unit_diag * xa[i] : (fa ? fa[i] : 0.0) - ba[i];
    if (f) check(VecRestoreArrayRead(f, &fa), "VecRestoreArrayRead");
    check(VecRestoreArray(b, &ba), "VecRestoreArray");
    check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
  }
  // Which off-process columns are eliminated: every rank's rows, gathered.
  std::vector<char> remote;
  if (n_parts_ == 2) {
    MPI_Comm comm;
    check(PetscObjectGetComm(PetscObject(k_), &comm), "PetscObjectGetComm");
    int size = 1;
    MPI_Comm_size(comm, &size);
    const int mine = int(rows.size());
    std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size) + 1, 0);
    MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int i = 0; i < size; ++i) offsets[std::size_t(i) + 1] = offsets[std::size_t(i)] + counts[std::size_t(i)];
    std::vector<PetscInt> all(std::size_t(offsets.back()));
    MPI_Allgatherv(rows.data(), mine, MPIU_INT, all.data(), counts.data(), offsets.data(), MPIU_INT, comm);
    std::sort(all.begin(), all.end());
    PetscInt ncols = 0;
    check(MatGetLocalSize(parts_[1].m, nullptr, &ncols), "MatGetLocalSize");
    remote.resize(std::size_t(ncols));
    for (PetscInt j = 0; j < ncols; ++j) remote[std::size_t(j)] = std::binary_search(all.begin(), all.end(), garray_[j]);
  }
  edit_values([&](int p, PetscScalar* v) {
    Part& q = parts_[p];
    const std::vector<char>& cols = p == 0 ? local : remote;
    for (PetscInt i = 0; i < nrows; ++i)
      for (PetscInt k = q.ia[i]; k < q.ia[i + 1]; ++k) {
        const bool whole_row = local[std::size_t(i)];
        if (!whole_row && !cols[std::size_t(q.ja[k])]) continue;
        q.saved_at.push_back(k);
        q.saved.push_back(v[k]);
        v[k] = whole_row && p == 0 && q.ja[k] == i ? unit_diag : 0.0;
      }
  });
  eliminated_ = true;
}

void FramedStiffness::restore() {
  if (!eliminated_) return;
  edit_values([&](int p, PetscScalar* v) {
    Part& q = parts_[p];
    for (std::size_t i = 0; i < q.saved_at.size(); ++i) v[q.saved_at[i]] = q.saved[i];
    q.saved_at.clear();
    q.saved.clear();
  });
  eliminated_ = false;
}

void FramedStiffness::reset(Mat k0) {
  restore();
  check(MatCopy(k0, k_, SAME_NONZERO_PATTERN), "MatCopy");
  for (std::size_t s = 0; s < face_slots_; ++s) {
    std::fill(&frames_[9 * s], &frames_[9 * s] + 9, 0.0);
    frames_[9 * s] = frames_[9 * s + 4] = frames_[9 * s + 8] = 1.0;
  }
  face_blocks_.clear();
}

void FramedStiffness::multiply_unrotated(Vec v, Vec out) {
  restore();
  if (!work_) check(MatCreateVecs(k_, &work_, nullptr), "MatCreateVecs");
  check(VecCopy(v, work_), "VecCopy");
  rotate_vector(work_, frames_, true);
  check(MatMult(k_, work_, out), "MatMult");
  rotate_vector(out, frames_, false);
}

void rotate_face_dofs(PetscScalar* a, PetscInt own_begin, PetscInt own_end, const std::vector<std::int32_t>& face_slot,
                      const std::vector<double>& frames, bool transpose) {
  for (PetscInt n = own_begin; n < own_end; ++n) {
    const std::int32_t s = face_slot[std::size_t(n)];
    if (s < 0) continue;
    double* x = a + 3 * std::size_t(n - own_begin);
    rotate_node(&frames[9 * std::size_t(s)], x, x, transpose);
  }
}

void rotate_face_dofs(Vec v, PetscInt own_begin, PetscInt own_end, const std::vector<std::int32_t>& face_slot,
                      const std::vector<double>& frames, bool transpose) {
  PetscScalar* a;
  check(VecGetArray(v, &a), "VecGetArray");
  rotate_face_dofs(a, own_begin, own_end, face_slot, frames, transpose);
  check(VecRestoreArray(v, &a), "VecRestoreArray");
}

void FramedStiffness::rotate_vector(Vec v, const std::vector<double>& frames, bool transpose) const {
  rotate_face_dofs(v, own_begin_, own_end_, face_slot_, frames, transpose);
}

}  // namespace wr
