#pragma once
// The block's stiffness in the face nodes' constraint frames, Khat = R^T K R, kept as one PETSc
// matrix that is rotated and reduced in place (sec. 4.2, Algorithm 1, steps 2-3).
//
// Why in place: the solver used to hold K, Khat and the reduced matrix A (active rows and
// columns eliminated) side by side, three matrices of K's size (3.1 GB each at 3.2M dofs; peak
// 13.6 GB on 2 ranks, 8.6 GB with this class). Here there is one:
// - set_frames(Q) turns Khat = R_old^T K R_old into R_new^T K R_new by the incremental rotation
//   D = Q_old^T Q_new of each face node (orthogonal, so rounding does not grow: after a thousand
//   rotations the entries differ from a direct R^T K R by ~1e-13 relative);
// - eliminate(rows) zeroes those rows and columns like MatZeroRowsColumns, saving what it
//   overwrites, and restore() writes it back (only rows and columns of face and top nodes are
//   eliminated, so the saved part is small).
// The values are edited through the AIJ arrays; the pattern never changes.
//
// Face blocks: set_face_blocks(C) adds a symmetric 3 x 3 block C_s (given in the global xyz
// frame) to each face node's diagonal block, so that the matrix is R^T (K + C) R; the Newton
// iteration on a curved obstacle puts the curvature of its contact constraints there
// (elastic_block_solve.cpp). Rotations carry the blocks along; they stay until replaced.
//
// Contract: K is an assembled AIJ matrix (MATSEQAIJ or MATMPIAIJ) with 3 dofs per node
// (dof = 3 node + c), rows partitioned by whole nodes, and, per node, three rows with one
// column pattern made of whole column nodes (what ElasticBlock assembles); the constructor
// checks this and throws std::runtime_error otherwise. Rows given to eliminate() must be owned.
// face_slot[node] is the node's index among the face nodes, or -1. Frames are 9 numbers per face
// slot, row-major Q with Q e_z = the constraint normal (every rank holds all of them). All
// methods but the accessors are collective.
#include <petscmat.h>

#include <cstdint>
#include <vector>

#include "lib/fem/framed_operator.hpp"

namespace wr {

// y = Q x (or Q^T x with transpose) for one node's 3 dofs, Q row-major: the one rotation that
// every framed operator and transfer applies (in place: y may be x).
inline void rotate_node(const double* q, const double* x, double* y, bool transpose) {
  double t[3];
  for (int i = 0; i < 3; ++i)
    t[i] = transpose ? q[i] * x[0] + q[3 + i] * x[1] + q[6 + i] * x[2] : q[3 * i] * x[0] + q[3 * i + 1] * x[1] + q[3 * i + 2] * x[2];
  y[0] = t[0], y[1] = t[1], y[2] = t[2];
}
// y += C x for one node's 3 x 3 block C (row-major).
inline void add_node_block(const double* c, const double* x, double* y) {
  for (int i = 0; i < 3; ++i) y[i] += c[3 * i] * x[0] + c[3 * i + 1] * x[1] + c[3 * i + 2] * x[2];
}

// a <- R a (transpose: R^T a) for the owned dofs `a` (3 per node from own_begin, as the matrix's
// rows): Q = frames[9 slot ...] (row-major) on every owned face node, the identity elsewhere.
void rotate_face_dofs(PetscScalar* a, PetscInt own_begin, PetscInt own_end, const std::vector<std::int32_t>& face_slot,
                      const std::vector<double>& frames, bool transpose);
// The same on a vector of that layout.
void rotate_face_dofs(Vec v, PetscInt own_begin, PetscInt own_end, const std::vector<std::int32_t>& face_slot,
                      const std::vector<double>& frames, bool transpose);

class FramedStiffness final : public FramedOperator {
 public:
  // Takes ownership of K (destroyed also when it is refused), whose frames are the identity.
  FramedStiffness(Mat K, PetscInt own_begin, PetscInt own_end, std::vector<std::int32_t> face_slot);
  ~FramedStiffness();
  FramedStiffness(const FramedStiffness&) = delete;
  FramedStiffness& operator=(const FramedStiffness&) = delete;

  Mat mat() const override { return k_; }  // Khat, reduced while an elimination is in force
  const std::vector<double>& frames() const override { return frames_; }

  // Khat <- R_new^T K R_new. Restores any elimination first.
  void set_frames(const std::vector<double>& frames) override;
  // Khat <- R^T (K + C) R with C the given blocks, 9 per face slot (row-major, global frame;
  // only the owned slots are read; all zero: K alone). Restores any elimination first.
  void set_face_blocks(const std::vector<double>& blocks) override;
  // Zeroes the rows and columns `rows` (global, owned), their diagonal set to unit_diag; b gets
  // f - Khat x on the other rows (f = 0 when null) and unit_diag x on these
  // (MatZeroRowsColumns's convention), so that the reduced system keeps x's values there.
  // x, b and f are distinct vectors like Khat's.
  void eliminate(const std::vector<PetscInt>& rows, double unit_diag, Vec x, Vec b, Vec f = nullptr) override;
  // Undoes eliminate() (no-op without one).
  void restore() override;
  // Khat <- K0 (frames the identity, no blocks), K0 a matrix of Khat's layout and pattern: a
  // fresh start whose later rotations do not depend on the earlier ones (same Mat object, so a
  // factorisation keeps its symbolic phase).
  void reset(Mat k0);
  // out = (K + C) v in the original frames (v not changed; out distinct from v). Restores any
  // elimination first.
  void multiply_unrotated(Vec v, Vec out) override;
  // v <- R^T v (transpose) or R v on the owned face nodes, with the given frames.
  void rotate_vector(Vec v, const std::vector<double>& frames, bool transpose) const override;

 private:
  struct Part {  // one AIJ block of the owned rows: the diagonal part, or the off-process part
    Mat m = nullptr;
    const PetscInt* ia = nullptr;  // CSR row starts (local rows)
    const PetscInt* ja = nullptr;  // columns: local (diagonal part) or into garray
    std::vector<PetscInt> saved_at;
    std::vector<PetscScalar> saved;
  };
  void map_structure();  // the parts' CSR arrays and the identity frames; checks the contract
  PetscInt global_column(const Part& p, PetscInt j) const;
  template <class F>
  void edit_values(F&& f);  // f(part index, values array) for the parts, then state bumps

  Mat k_ = nullptr;
  PetscInt own_begin_ = 0, own_end_ = 0;  // owned node ids
  std::vector<std::int32_t> face_slot_;
  std::vector<double> frames_;  // 9 per face slot; identity at the start
  std::vector<double> face_blocks_;  // C, 9 per face slot (empty: none yet)
  Part parts_[2];
  int n_parts_ = 1;
  const PetscInt* garray_ = nullptr;  // global columns of the off-process part
  Vec work_ = nullptr;
  bool eliminated_ = false;
  std::size_t face_slots_ = 0;
};

}  // namespace wr
