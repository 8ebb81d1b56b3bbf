#pragma once
// The two linear solvers of the thin-film flow (thin_film_flow.hpp) on its symmetric positive
// definite system A X = B, B with one column per imposed gradient:
//  - CHOLMOD's supernodal Cholesky (SuiteSparse, through Eigen's CholmodSupport): one
//    factorisation, every column solved with it; fill-reducing ordering chosen by CHOLMOD (AMD,
//    METIS when AMD fills much).
//  - PETSc CG with the GAMG preconditioner (sequential AIJ matrix), to a relative residual
//    `tolerance` in the true (unpreconditioned) norm; one hierarchy for all columns. Needs PETSc
//    started (lib/fem/petsc_session.hpp): std::logic_error otherwise. Options prefix "flow_".
// Both throw NumericalError when the solve fails (not positive definite, CG diverged or ran out
// of iterations) and report the larger relative residual |b - A x| / |b| over the columns.
#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace wr::flow {

struct LinearSolve {
  Eigen::MatrixXd x;
  int iterations = 0;  // CG iterations of the longest column solve; 0 for CHOLMOD
  double residual = 0;
};

// `a`: full (both triangles) symmetric positive definite, column-major; `b`: a.rows() x k.
LinearSolve solve_cholmod(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& b);
LinearSolve solve_amg(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& b, double tolerance);

// max over columns of |b - A x| / |b| (0 for a zero column).
double relative_residual(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x);

}  // namespace wr::flow
