#pragma once
// Non-negative least squares: min ||A x - b||_2 subject to x >= 0 (Lawson & Hanson, "Solving
// Least Squares Problems", 1974, ch. 23, algorithm NNLS). Small dense problems (a Prony fit:
// tens of unknowns, hundreds of rows); the unconstrained subproblems use Eigen's
// column-pivoting Householder QR.
#include <Eigen/Dense>

namespace wr {

struct NnlsResult {
  Eigen::VectorXd x;
  double residual_norm = 0;  // ||A x - b||
  int iterations = 0;
  bool converged = false;    // false: the iteration limit (3 n) was reached
};

NnlsResult solve_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace wr
