#include "lib/core/least_squares.hpp"

namespace wr {

std::optional<Eigen::VectorXd> least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < A.cols()) return std::nullopt;
  return Eigen::VectorXd(qr.solve(b));
}

Eigen::VectorXd solve_normal_equations(const Eigen::MatrixXd& N, const Eigen::VectorXd& r) {
  // Robust Cholesky (pivoted LDL^T): a zero pivot (no samples in a direction) leaves that
  // unknown at zero instead of dividing by it.
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(N);
  Eigen::VectorXd x = ldlt.solve(r);
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!std::isfinite(x(i))) x(i) = 0;
  return x;
}

}  // namespace wr
