#include "lib/flow/flow_solvers.hpp"

#include <petscksp.h>

#include <Eigen/CholmodSupport>
#include <stdexcept>
#include <string>

#include "lib/core/errors.hpp"
#include "lib/fem/petsc_session.hpp"

namespace wr::flow {

double relative_residual(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x) {
  double worst = 0;
  for (Eigen::Index k = 0; k < b.cols(); ++k) {
    const double nb = b.col(k).norm();
    if (nb > 0) worst = std::max(worst, (b.col(k) - a * x.col(k)).norm() / nb);
  }
  return worst;
}

LinearSolve solve_cholmod(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& b) {
  // Lower: CHOLMOD reads one triangle of the symmetric matrix (stype -1).
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  llt.compute(a);
  if (llt.info() != Eigen::Success)
    throw NumericalError("flow (cholmod)", "the Reynolds system is not positive definite (Cholesky failed)");
  LinearSolve s;
  s.x = llt.solve(b);
  if (llt.info() != Eigen::Success) throw NumericalError("flow (cholmod)", "the triangular solves failed");
  s.residual = relative_residual(a, b, s.x);
  return s;
}

namespace {

// RAII holders of the PETSc objects of one solve.
struct PetscObjects {
  Mat a = nullptr;
  Vec b = nullptr, x = nullptr;
  KSP ksp = nullptr;
  ~PetscObjects() {
    if (ksp) KSPDestroy(&ksp);
    if (x) VecDestroy(&x);
    if (b) VecDestroy(&b);
    if (a) MatDestroy(&a);
  }
};

// The symmetric matrix as a sequential AIJ (CSR) matrix: column j of the CSC matrix is row j.
Mat to_petsc(const Eigen::SparseMatrix<double>& a) {
  using petsc::check;
  const PetscInt n = static_cast<PetscInt>(a.rows());
  std::vector<PetscInt> nnz(static_cast<std::size_t>(n));
  for (PetscInt j = 0; j < n; ++j) nnz[std::size_t(j)] = static_cast<PetscInt>(a.outerIndexPtr()[j + 1] - a.outerIndexPtr()[j]);
  Mat m = nullptr;
  check(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, nnz.data(), &m), "MatCreateSeqAIJ");
  std::vector<PetscInt> cols;
  for (PetscInt j = 0; j < n; ++j) {
    const int begin = a.outerIndexPtr()[j], end = a.outerIndexPtr()[j + 1];
    cols.assign(a.innerIndexPtr() + begin, a.innerIndexPtr() + end);
    check(MatSetValues(m, 1, &j, end - begin, cols.data(), a.valuePtr() + begin, INSERT_VALUES), "MatSetValues");
  }
  check(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatSetOption(m, MAT_SPD, PETSC_TRUE), "MatSetOption");
  return m;
}

}  // namespace

LinearSolve solve_amg(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& b, double tolerance) {
  using petsc::check;
  PetscBool started = PETSC_FALSE;
  PetscInitialized(&started);
  if (!started) throw std::logic_error("the amg flow solver needs PETSc started (wr::PetscSession)");
  const PetscInt n = static_cast<PetscInt>(a.rows());
  PetscObjects o;
  o.a = to_petsc(a);
  check(MatCreateVecs(o.a, &o.x, &o.b), "MatCreateVecs");
  check(KSPCreate(PETSC_COMM_SELF, &o.ksp), "KSPCreate");
  check(KSPSetOperators(o.ksp, o.a, o.a), "KSPSetOperators");
  check(KSPSetType(o.ksp, KSPCG), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(o.ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  // Drop weak couplings when aggregating: next to a contact line g^3 falls by decades within a
  // cell or two, and aggregates across those faces made CG's iterations grow with the grid (57,
  // 334, 1467 at 256^2 ... 1024^2 with PETSc's default 0). Measured on a 512^2 elastic gap
  // (sigma* 0.1): threshold 0: 145 iterations 6.5 s; 0.02: 42, 2.8 s; 0.05: 35, 3.4 s; 0.1: 101;
  // 0.2: 738 (docs/performance.md). -flow_pc_gamg_threshold overrides it.
  PetscReal threshold[] = {0.02};
  check(PCGAMGSetThreshold(pc, threshold, 1), "PCGAMGSetThreshold");
  // The true residual, so that the tolerance means the same as CHOLMOD's reported residual.
  check(KSPSetNormType(o.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(o.ksp, tolerance, 0.0, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  check(KSPSetOptionsPrefix(o.ksp, "flow_"), "KSPSetOptionsPrefix");
  check(KSPSetFromOptions(o.ksp), "KSPSetFromOptions");
  check(KSPSetUp(o.ksp), "KSPSetUp");
  LinearSolve s;
  s.x.resize(b.rows(), b.cols());
  std::vector<PetscInt> idx(static_cast<std::size_t>(n));
  for (PetscInt i = 0; i < n; ++i) idx[std::size_t(i)] = i;
  for (Eigen::Index k = 0; k < b.cols(); ++k) {
    check(VecSetValues(o.b, n, idx.data(), b.col(k).data(), INSERT_VALUES), "VecSetValues");
    check(VecAssemblyBegin(o.b), "VecAssemblyBegin");
    check(VecAssemblyEnd(o.b), "VecAssemblyEnd");
    check(VecSet(o.x, 0.0), "VecSet");
    check(KSPSolve(o.ksp, o.b, o.x), "KSPSolve");
    KSPConvergedReason why;
    PetscInt its = 0;
    check(KSPGetConvergedReason(o.ksp, &why), "KSPGetConvergedReason");
    check(KSPGetIterationNumber(o.ksp, &its), "KSPGetIterationNumber");
    if (why < 0)
      throw NumericalError("flow (amg)", std::string("CG did not converge: ") + KSPConvergedReasons[why] + " after " +
                                             std::to_string(its) + " iterations");
    s.iterations = std::max(s.iterations, static_cast<int>(its));
    const PetscScalar* v = nullptr;
    check(VecGetArrayRead(o.x, &v), "VecGetArrayRead");
    for (PetscInt i = 0; i < n; ++i) s.x(i, k) = v[i];
    check(VecRestoreArrayRead(o.x, &v), "VecRestoreArrayRead");
  }
  s.residual = relative_residual(a, b, s.x);
  return s;
}

}  // namespace wr::flow
