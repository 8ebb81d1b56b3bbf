#include "lib/core/nnls.hpp"

#include <limits>
#include <vector>

namespace wr {
namespace {

// Least squares on the passive columns only; the others are zero.
Eigen::VectorXd passive_solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const std::vector<bool>& passive) {
  std::vector<Eigen::Index> cols;
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    if (passive[static_cast<std::size_t>(j)]) cols.push_back(j);
  Eigen::MatrixXd Ap(A.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k) Ap.col(static_cast<Eigen::Index>(k)) = A.col(cols[k]);
  const Eigen::VectorXd zp = Ap.colPivHouseholderQr().solve(b);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(A.cols());
  for (std::size_t k = 0; k < cols.size(); ++k) z(cols[k]) = zp(static_cast<Eigen::Index>(k));
  return z;
}

}  // namespace

NnlsResult solve_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const Eigen::Index n = A.cols();
  NnlsResult out;
  out.x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  const double tol = 10 * std::numeric_limits<double>::epsilon() * A.norm() * std::max<Eigen::Index>(A.rows(), n);
  const int max_iter = static_cast<int>(3 * n) + 10;
  for (out.iterations = 0; out.iterations < max_iter; ++out.iterations) {
    const Eigen::VectorXd w = A.transpose() * (b - A * out.x);
    Eigen::Index best = -1;
    double wmax = tol;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!passive[static_cast<std::size_t>(j)] && w(j) > wmax) {
        wmax = w(j);
        best = j;
      }
    if (best < 0) {
      out.converged = true;
      break;
    }
    passive[static_cast<std::size_t>(best)] = true;
    for (int inner = 0; inner < max_iter; ++inner) {  // step towards the passive solution until feasible
      const Eigen::VectorXd z = passive_solve(A, b, passive);
      double alpha = 1;
      bool feasible = true;
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[static_cast<std::size_t>(j)] && z(j) <= 0) {
          feasible = false;
          const double d = out.x(j) - z(j);
          if (d > 0) alpha = std::min(alpha, out.x(j) / d);
        }
      if (feasible) {
        out.x = z;
        break;
      }
      out.x += alpha * (z - out.x);
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[static_cast<std::size_t>(j)] && out.x(j) <= tol) {
          passive[static_cast<std::size_t>(j)] = false;
          out.x(j) = 0;
        }
    }
  }
  out.residual_norm = (A * out.x - b).norm();
  return out;
}

}  // namespace wr
