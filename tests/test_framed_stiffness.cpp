// The stiffness kept in the constraint frames (lib/fem/framed_stiffness.hpp) against direct
// PETSc products. Runs under MPI too (ctest runs it on 1 and 2 ranks).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "lib/fem/framed_stiffness.hpp"

namespace wr {
namespace {

// The stiffness kept in the constraint frames (lib/fem/framed_stiffness.hpp) against the
// direct products: two successive incremental rotations against R^T K R by MatPtAP, the
// in-place elimination against MatZeroRowsColumns on a copy (matrix and right-hand side), and
// restore() back to the rotated matrix exactly. A chain of 12 nodes coupled to their
// neighbours up to two away (random symmetric 3 x 3 blocks), every second node a face node;
// on 2 ranks the chain is split, so off-process columns are rotated and eliminated too.
Mat chain_stiffness(int nodes, PetscInt& own_begin, PetscInt& own_end) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  own_begin = PetscInt(nodes * rank / size);
  own_end = PetscInt(nodes * (rank + 1) / size);
  Mat k;
  MatCreateAIJ(PETSC_COMM_WORLD, 3 * (own_end - own_begin), 3 * (own_end - own_begin), PETSC_DETERMINE,
               PETSC_DETERMINE, 15, nullptr, 15, nullptr, &k);
  auto entry = [](int a, int b, int i, int j) {  // symmetric in (a, i) <-> (b, j)
    const int lo = std::min(3 * a + i, 3 * b + j), hi = std::max(3 * a + i, 3 * b + j);
    return lo == hi ? 20.0 : std::sin(1.0 + lo * 7.3 + hi * 3.1);
  };
  for (PetscInt a = own_begin; a < own_end; ++a)
    for (int b = std::max(0, int(a) - 2); b <= std::min(nodes - 1, int(a) + 2); ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) MatSetValue(k, 3 * a + i, 3 * b + j, entry(int(a), b, i, j), INSERT_VALUES);
  MatAssemblyBegin(k, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(k, MAT_FINAL_ASSEMBLY);
  return k;
}

std::vector<double> random_frames(std::size_t slots, double seed) {
  std::vector<double> q(9 * slots);
  for (std::size_t s = 0; s < slots; ++s) {
    // Rodrigues rotation about a varying axis by a varying angle.
    const double ax = std::sin(seed + s), ay = std::cos(2 * seed + s), az = 0.5 + std::sin(3 * s + seed);
    const double n = std::sqrt(ax * ax + ay * ay + az * az), x = ax / n, y = ay / n, z = az / n;
    const double t = 0.3 + 0.2 * std::sin(seed * s), c = std::cos(t), si = std::sin(t), v = 1 - c;
    const double r[9] = {c + x * x * v,     x * y * v - z * si, x * z * v + y * si, y * x * v + z * si, c + y * y * v,
                         y * z * v - x * si, z * x * v - y * si, z * y * v + x * si, c + z * z * v};
    std::copy(r, r + 9, &q[9 * s]);
  }
  return q;
}

// max |v - ref| / max |ref|.
double relative_difference(Vec v, Vec ref) {
  Vec d;
  VecDuplicate(v, &d);
  VecWAXPY(d, -1.0, ref, v);
  double err = 0, norm = 0;
  VecNorm(d, NORM_INFINITY, &err);
  VecNorm(ref, NORM_INFINITY, &norm);
  VecDestroy(&d);
  return err / norm;
}

double difference_norm(Mat a, Mat b) {
  Mat d;
  MatDuplicate(a, MAT_COPY_VALUES, &d);
  MatAXPY(d, -1.0, b, DIFFERENT_NONZERO_PATTERN);
  double n = 0;
  MatNorm(d, NORM_FROBENIUS, &n);
  MatDestroy(&d);
  return n;
}

// R: block diagonal, the frame of each face node (slot[node] >= 0), the identity elsewhere.
Mat rotation_matrix(const std::vector<double>& q, const std::vector<std::int32_t>& slot, PetscInt b0, PetscInt b1) {
  Mat r;
  MatCreateAIJ(PETSC_COMM_WORLD, 3 * (b1 - b0), 3 * (b1 - b0), PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr,
               &r);
  for (PetscInt a = b0; a < b1; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const std::int32_t s = slot[std::size_t(a)];
        const double v = s < 0 ? double(i == j) : q[9 * std::size_t(s) + 3 * i + j];
        MatSetValue(r, 3 * a + i, 3 * a + j, v, INSERT_VALUES);
      }
  MatAssemblyBegin(r, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(r, MAT_FINAL_ASSEMBLY);
  return r;
}

TEST(FramedStiffness, RotatesAndEliminatesLikeTheDirectProducts) {
  const int nodes = 12;
  PetscInt b0, b1;
  Mat k = chain_stiffness(nodes, b0, b1);
  Mat k_copy;
  MatDuplicate(k, MAT_COPY_VALUES, &k_copy);
  std::vector<std::int32_t> slot(nodes, -1);
  int slots = 0;
  for (int n = 0; n < nodes; n += 2) slot[std::size_t(n)] = slots++;
  FramedStiffness fs(k, b0, b1, slot);
  double k_norm = 0;
  MatNorm(k_copy, NORM_FROBENIUS, &k_norm);

  auto rotation = [&](const std::vector<double>& q) { return rotation_matrix(q, slot, b0, b1); };
  Mat direct = nullptr;
  for (double seed : {0.4, 1.7}) {
    const std::vector<double> q = random_frames(std::size_t(slots), seed);
    fs.set_frames(q);
    Mat r = rotation(q);
    if (direct) MatDestroy(&direct);
    MatPtAP(k_copy, r, MAT_INITIAL_MATRIX, 2.0, &direct);
    MatDestroy(&r);
    EXPECT_LT(difference_norm(fs.mat(), direct), 1e-13 * k_norm) << "seed " << seed;
  }

  // Eliminate some owned rows (z of every third node, x of node 1) like MatZeroRowsColumns.
  std::vector<PetscInt> rows;
  for (PetscInt a = b0; a < b1; ++a) {
    if (a % 3 == 0) rows.push_back(3 * a + 2);
    if (a == 1) rows.push_back(3 * a);
  }
  Vec x, b_ref, b;
  MatCreateVecs(k_copy, &x, nullptr);
  VecDuplicate(x, &b_ref);
  VecDuplicate(x, &b);
  for (PetscInt i = 3 * b0; i < 3 * b1; ++i) VecSetValue(x, i, 0.01 * double(i) - 0.1, INSERT_VALUES);
  VecAssemblyBegin(x);
  VecAssemblyEnd(x);
  VecSet(b_ref, 0.0);
  MatZeroRowsColumns(direct, PetscInt(rows.size()), rows.data(), 5.0, x, b_ref);
  fs.eliminate(rows, 5.0, x, b);
  EXPECT_LT(difference_norm(fs.mat(), direct), 1e-13 * k_norm);
  EXPECT_LT(relative_difference(b, b_ref), 1e-13);

  // restore() gives back the rotated matrix; K v in the original frames is K's.
  Mat rotated;
  MatDuplicate(fs.mat(), MAT_COPY_VALUES, &rotated);
  fs.restore();
  fs.eliminate(rows, 5.0, x, b);
  fs.restore();
  Mat q2 = rotation(fs.frames());
  Mat again;
  MatPtAP(k_copy, q2, MAT_INITIAL_MATRIX, 2.0, &again);
  EXPECT_LT(difference_norm(fs.mat(), again), 1e-13 * k_norm);
  Vec kv, kv_ref;
  VecDuplicate(x, &kv);
  VecDuplicate(x, &kv_ref);
  fs.multiply_unrotated(x, kv);
  MatMult(k_copy, x, kv_ref);
  EXPECT_LT(relative_difference(kv, kv_ref), 1e-13);
  for (Vec* v : {&x, &b_ref, &b, &kv, &kv_ref}) VecDestroy(v);
  for (Mat* m : {&k_copy, &direct, &rotated, &q2, &again}) MatDestroy(m);
}

// Face blocks (the Newton iteration's curvature terms): with blocks C set, the matrix is
// R^T (K + C) R, through later rotations and replacements of C too, and f enters the
// eliminated system's right-hand side on the free rows.
TEST(FramedStiffness, FaceBlocksAddToTheRotatedDiagonal) {
  const int nodes = 12;
  PetscInt b0, b1;
  Mat k = chain_stiffness(nodes, b0, b1);
  std::vector<std::int32_t> slot(nodes, -1);
  int slots = 0;
  for (int n = 1; n < nodes; n += 2) slot[std::size_t(n)] = slots++;
  Mat kc;  // K + C, assembled directly
  MatDuplicate(k, MAT_COPY_VALUES, &kc);
  FramedStiffness fs(k, b0, b1, slot);
  double k_norm = 0;
  MatNorm(kc, NORM_FROBENIUS, &k_norm);
  auto blocks_of = [&](double seed) {
    std::vector<double> c(9 * std::size_t(slots), 0.0);
    for (int s = 0; s < slots; ++s) {
      const double a = std::sin(seed + s), b = 0.3 * std::cos(seed * s), d = -0.7 + std::sin(2 * s);
      const double v[9] = {a, b, 0, b, d, 0, 0, 0, 0};
      std::copy(v, v + 9, &c[9 * std::size_t(s)]);
    }
    return c;
  };
  const std::vector<double> c1 = blocks_of(0.3), c2 = blocks_of(1.1);
  fs.set_frames(random_frames(std::size_t(slots), 0.4));
  fs.set_face_blocks(c1);
  fs.set_frames(random_frames(std::size_t(slots), 1.7));  // the blocks rotate along
  fs.set_face_blocks(c2);                                  // and are replaced, not added
  for (PetscInt a = b0; a < b1; ++a) {
    const std::int32_t s = slot[std::size_t(a)];
    if (s < 0) continue;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) MatSetValue(kc, 3 * a + i, 3 * a + j, c2[9 * std::size_t(s) + 3 * i + j], ADD_VALUES);
  }
  MatAssemblyBegin(kc, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(kc, MAT_FINAL_ASSEMBLY);
  Mat r = rotation_matrix(fs.frames(), slot, b0, b1), direct;
  MatPtAP(kc, r, MAT_INITIAL_MATRIX, 2.0, &direct);
  EXPECT_LT(difference_norm(fs.mat(), direct), 1e-13 * k_norm);

  // b = f - Khat x_e on the free rows, unit_diag x on the eliminated ones.
  std::vector<PetscInt> rows;
  for (PetscInt a = b0; a < b1; ++a)
    if (a % 4 == 1) rows.push_back(3 * a + 2);
  Vec x, f, b, b_ref;
  MatCreateVecs(direct, &x, nullptr);
  for (Vec* v : {&f, &b, &b_ref}) VecDuplicate(x, v);
  for (PetscInt i = 3 * b0; i < 3 * b1; ++i) {
    VecSetValue(x, i, 0.01 * double(i) - 0.1, INSERT_VALUES);
    VecSetValue(f, i, std::cos(double(i)), INSERT_VALUES);
  }
  for (Vec v : {x, f}) {
    VecAssemblyBegin(v);
    VecAssemblyEnd(v);
  }
  VecCopy(f, b_ref);
  MatZeroRowsColumns(direct, PetscInt(rows.size()), rows.data(), 5.0, x, b_ref);
  fs.eliminate(rows, 5.0, x, b, f);
  EXPECT_LT(difference_norm(fs.mat(), direct), 1e-13 * k_norm);
  EXPECT_LT(relative_difference(b, b_ref), 1e-13);
  for (Vec* v : {&x, &f, &b, &b_ref}) VecDestroy(v);
  for (Mat* m : {&kc, &r, &direct}) MatDestroy(m);
}

}  // namespace
}  // namespace wr
