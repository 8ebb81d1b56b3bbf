#include "lib/fem/matrix_free_stiffness.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "lib/fem/elastic_block_impl.hpp"
#include "lib/fem/local_bricks.hpp"

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
  for (int e = 0; e < g.layers(); ++e) {
    layer_k_.push_back(block_detail::brick_stiffness(g.hx(g.layer_level(e)), g.hy(g.layer_level(e)),
                                                     g.planes()[e + 1].z - g.planes()[e].z, young, poisson));
    for (int q = 0; q < 24; ++q)
      for (int r = 0; r < 24; ++r) columns_.push_back(layer_k_.back()[std::size_t(r * 24 + q)]);
  }
  std::unordered_map<std::int32_t, std::int32_t> ghost_slot;
  auto local = [&](std::int32_t id) {
    if (id >= own_begin_ && id < own_end_) return id - own_begin_;
    const auto [it, added] = ghost_slot.try_emplace(id, n_own + std::int32_t(ghost_ids_.size()));
    if (added) ghost_ids_.push_back(id);
    return it->second;
  };
  for_each_local_brick(g, rank, own_begin_, own_end_, [&](int e, const std::vector<std::int32_t>& ids, const std::vector<double>& w) {
    layer_.push_back(std::int16_t(e));
    const std::size_t n = ids.size();
    for (int c = 0; c < 8; ++c) {
      corner_.push_back(std::uint32_t(node_.size()));
      for (std::size_t p = 0; p < n; ++p)
        if (w[c * n + p] != 0) {
          node_.push_back(local(ids[p]));
          weight_.push_back(w[c * n + p]);
        }
    }
  });
  corner_.push_back(std::uint32_t(node_.size()));  // the last brick's end (brick b's corners: 8 b ... 8 b + 8)
  // The scatter of x's owned and ghost dofs into local_.
  std::vector<PetscInt> from;
  from.reserve(3 * (std::size_t(n_own) + ghost_ids_.size()));
  for (std::int32_t id = own_begin_; id < own_end_; ++id)
    for (int c = 0; c < 3; ++c) from.push_back(3 * PetscInt(id) + c);
  for (std::int32_t id : ghost_ids_)
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
  return 2 * layer_k_.size() * sizeof(layer_k_[0]) + layer_.size() * sizeof(std::int16_t) + corner_.size() * sizeof(std::uint32_t) +
         node_.size() * sizeof(std::int32_t) + weight_.size() * sizeof(double) + std::size_t(n) * sizeof(double);
}

namespace {

// y (owned rows, zeroed first) += the bricks' C^T K C x. The layer matrices are stored column by
// column, so that K xe is a sum of columns scaled by xe[q]: the compiler vectorises it over the
// rows without reassociating any sum, and the AVX2 clone (chosen at run time where the CPU has
// it; no FMA) gives the same bits as the SSE2 one.
__attribute__((target_clones("avx2", "default"))) void apply_bricks(
    std::size_t bricks, const std::int16_t* layer, const std::uint32_t* corner, const std::int32_t* node,
    const double* weight, const double* columns, const double* xl, double* yo, std::int32_t n_own) {
  for (std::size_t b = 0; b < bricks; ++b) {
    const std::uint32_t* cs = corner + 8 * b;
    // Eight entries are eight corners on their own nodes with weight 1 (a brick without hanging
    // corners): gathered and scattered directly, with the same bits as the general path.
    const bool plain = cs[8] - cs[0] == 8;
    // The corners' displacements through the hanging-node interpolation, then the brick's forces.
    double xe[24];
    if (plain) {
      for (int c = 0; c < 8; ++c) {
        const double* xp = xl + 3 * std::size_t(node[cs[0] + c]);
        xe[3 * c] = xp[0], xe[3 * c + 1] = xp[1], xe[3 * c + 2] = xp[2];
      }
    } else {
      for (int c = 0; c < 8; ++c) {
        double v0 = 0, v1 = 0, v2 = 0;
        for (std::uint32_t k = cs[c]; k < cs[c + 1]; ++k) {
          const double* xp = xl + 3 * std::size_t(node[k]);
          const double w = weight[k];
          v0 += w * xp[0];
          v1 += w * xp[1];
          v2 += w * xp[2];
        }
        xe[3 * c] = v0, xe[3 * c + 1] = v1, xe[3 * c + 2] = v2;
      }
    }
    const double* kt = columns + std::size_t(layer[b]) * 576;
    double ye[24] = {};
    for (int q = 0; q < 24; ++q) {
      const double xq = xe[q];
      for (int r = 0; r < 24; ++r) ye[r] += kt[q * 24 + r] * xq;
    }
    if (plain) {
      for (int c = 0; c < 8; ++c) {
        const std::int32_t p = node[cs[0] + c];
        if (p >= n_own) continue;  // another rank's row
        double* yp = yo + 3 * std::size_t(p);
        yp[0] += ye[3 * c], yp[1] += ye[3 * c + 1], yp[2] += ye[3 * c + 2];
      }
      continue;
    }
    for (int c = 0; c < 8; ++c)
      for (std::uint32_t k2 = cs[c]; k2 < cs[c + 1]; ++k2) {
        const std::int32_t p = node[k2];
        if (p >= n_own) continue;  // another rank's row
        const double w = weight[k2];
        double* yp = yo + 3 * std::size_t(p);
        yp[0] += w * ye[3 * c], yp[1] += w * ye[3 * c + 1], yp[2] += w * ye[3 * c + 2];
      }
  }
}

}  // namespace

void MatrixFreeStiffness::multiply(Vec x, Vec y) const {
  check(VecScatterBegin(scatter_, x, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(scatter_, x, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* xl = nullptr;
  PetscScalar* yo = nullptr;
  check(VecGetArrayRead(local_, &xl), "VecGetArrayRead");
  check(VecGetArray(y, &yo), "VecGetArray");
  const std::int32_t n_own = own_end_ - own_begin_;
  std::fill(yo, yo + 3 * std::size_t(n_own), 0.0);
  apply_bricks(layer_.size(), layer_.data(), corner_.data(), node_.data(), weight_.data(), columns_.data(), xl, yo, n_own);
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

// Calls f(p, w, k, a, c) for every pair of corners (a, c) of a brick that both lie on the owned
// local node p: w their weights' product, k the brick's layer matrix (row-major). The node's
// 3 x 3 diagonal block is the sum of w K8[3a + i][3c + j] over these pairs.
template <class F>
void MatrixFreeStiffness::for_each_self_pair(F&& f) const {
  const std::int32_t n_own = own_end_ - own_begin_;
  for (std::size_t b = 0; b < layer_.size(); ++b) {
    const std::uint32_t* cs = &corner_[8 * b];
    const double* k = layer_k_[std::size_t(layer_[b])].data();
    for (int a = 0; a < 8; ++a)
      for (std::uint32_t ka = cs[a]; ka < cs[a + 1]; ++ka) {
        const std::int32_t p = node_[ka];
        if (p >= n_own) continue;
        for (int c = 0; c < 8; ++c)
          for (std::uint32_t kc = cs[c]; kc < cs[c + 1]; ++kc)
            if (node_[kc] == p) f(p, weight_[ka] * weight_[kc], k, a, c);
      }
  }
}

void MatrixFreeStiffness::diagonal(Vec d) const {
  PetscScalar* dd = nullptr;
  check(VecGetArray(d, &dd), "VecGetArray");
  std::fill(dd, dd + 3 * std::size_t(own_end_ - own_begin_), 0.0);
  for_each_self_pair([&](std::int32_t p, double w, const double* k, int a, int c) {
    for (int i = 0; i < 3; ++i) dd[3 * std::size_t(p) + i] += w * k[(3 * a + i) * 24 + 3 * c + i];
  });
  check(VecRestoreArray(d, &dd), "VecRestoreArray");
}

void MatrixFreeStiffness::face_diagonal_blocks(const std::vector<std::int32_t>& face_slot, std::vector<double>& blocks) const {
  for (std::int32_t p = 0; p < own_end_ - own_begin_; ++p) {
    const std::int32_t s = face_slot[std::size_t(own_begin_ + p)];
    if (s >= 0) std::fill(&blocks[9 * std::size_t(s)], &blocks[9 * std::size_t(s)] + 9, 0.0);
  }
  for_each_self_pair([&](std::int32_t p, double w, const double* k, int a, int c) {
    const std::int32_t s = face_slot[std::size_t(own_begin_ + p)];
    if (s < 0) return;
    double* out = &blocks[9 * std::size_t(s)];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out[3 * i + j] += w * k[(3 * a + i) * 24 + 3 * c + j];
  });
}

}  // namespace wr
