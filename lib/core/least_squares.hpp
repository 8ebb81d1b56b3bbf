#pragma once
// Small dense least squares (Eigen): the fits of texture spectra, area-load curves and report
// peaks. Column-pivoted Householder QR on the design matrix, not the normal equations: the
// error grows with cond(A), not cond(A)^2 (the quartic's basis s..s^4 has cond(A) ~ 1e3).
#include <optional>

#include <Eigen/Dense>

namespace wr {

// argmin |A x - b|_2, or nullopt when A's columns are dependent (numerical rank < cols: e.g. a
// quartic through repeated abscissae). Rows may be pre-scaled by sqrt(weight).
std::optional<Eigen::VectorXd> least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

// Solves the symmetric positive semi-definite normal equations N x = r accumulated elsewhere (a
// map's mean plane: millions of rows that are never stored); zero where N's pivot is zero.
Eigen::VectorXd solve_normal_equations(const Eigen::MatrixXd& N, const Eigen::VectorXd& r);

}  // namespace wr
