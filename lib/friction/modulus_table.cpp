#include "lib/friction/modulus_table.hpp"

#include <cmath>
#include <sstream>

#include "lib/core/errors.hpp"
#include "lib/core/nnls.hpp"

namespace wr {

void check_modulus_table(const ModulusTable& t, const std::string& source) {
  if (t.omega.size() != t.storage.size() || t.omega.size() != t.loss.size())
    throw InputError(source, "table: omega_rad_s, storage_pa and loss_pa must have the same length");
  if (t.omega.size() < 4) throw InputError(source, "table: give at least 4 frequencies");
  if (t.omega.size() > kMaxTableRows)
    throw InputError(source, "table: " + std::to_string(t.omega.size()) + " frequencies; at most " +
                                 std::to_string(kMaxTableRows) + " are fitted (thin the table)");
  for (std::size_t i = 0; i < t.omega.size(); ++i) {
    const std::string at = "table row " + std::to_string(i);
    if (!(t.omega[i] > 0 && std::isfinite(t.omega[i]))) throw InputError(source, at + ": omega must be positive (rad/s)");
    if (!(t.omega[i] >= kMinOmega && t.omega[i] <= kMaxOmega)) throw InputError(source, at + ": omega must lie in [1e-30, 1e30] rad/s");
    if (i > 0 && !(t.omega[i] > t.omega[i - 1])) throw InputError(source, at + ": frequencies must ascend");
    if (!(t.storage[i] > 0 && std::isfinite(t.storage[i]))) throw InputError(source, at + ": storage modulus must be positive (Pa)");
    if (!(t.loss[i] > 0 && std::isfinite(t.loss[i]))) throw InputError(source, at + ": loss modulus must be positive (Pa)");
  }
  if (std::log10(t.omega.back() / t.omega.front()) > kMaxTableDecades)
    throw InputError(source, "table: the frequencies span more than 40 decades (rad/s); a master curve spans 10 to 25");
}

PronyFit fit_prony(const ModulusTable& t) {
  const double lo = -std::log10(t.omega.back()) - 1, hi = -std::log10(t.omega.front()) + 1;
  const int m = static_cast<int>(std::ceil((hi - lo) * kTermsPerDecade)) + 1;
  std::vector<double> tau(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) tau[static_cast<std::size_t>(i)] = std::pow(10.0, lo + (hi - lo) * i / (m - 1));
  const Eigen::Index rows = static_cast<Eigen::Index>(2 * t.omega.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, m + 1);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(rows);
  for (std::size_t k = 0; k < t.omega.size(); ++k) {
    const Eigen::Index rs = static_cast<Eigen::Index>(2 * k), rl = rs + 1;
    A(rs, 0) = 1 / t.storage[k];
    for (int i = 0; i < m; ++i) {
      const double x = t.omega[k] * tau[static_cast<std::size_t>(i)];
      A(rs, i + 1) = x * x / (1 + x * x) / t.storage[k];
      A(rl, i + 1) = x / (1 + x * x) / t.loss[k];
    }
  }
  // Columns scaled to unit norm: the moduli span decades and NNLS's tolerances are absolute.
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < A.cols(); ++j) A.col(j) /= scale(j);
  const NnlsResult r = solve_nnls(A, b);
  PronyFit fit;
  fit.e_relaxed = r.x(0) / scale(0);
  for (int i = 0; i < m; ++i) {
    const double de = r.x(i + 1) / scale(i + 1);
    if (de > 0) fit.terms.push_back({tau[static_cast<std::size_t>(i)], de});
  }
  const Eigen::VectorXd res = A * r.x - b;
  double sum = 0;
  for (Eigen::Index k = 0; k < rows; ++k) {
    sum += res(k) * res(k);
    if (std::abs(res(k)) > fit.max_misfit) {
      fit.max_misfit = std::abs(res(k));
      fit.worst_omega = t.omega[static_cast<std::size_t>(k / 2)];
      fit.worst_is_loss = k % 2 == 1;
    }
  }
  fit.rms_misfit = std::sqrt(sum / static_cast<double>(rows));
  return fit;
}

PronyFit causal_prony_fit(const ModulusTable& t, const std::string& source) {
  check_modulus_table(t, source);
  PronyFit fit = fit_prony(t);
  if (!(fit.e_relaxed > 0))
    throw InputError(source, "table: not causal: the storage modulus does not level off to a positive rubbery plateau");
  if (fit.max_misfit > kCausalityTolerance) {
    std::ostringstream s;
    s.precision(3);
    s << "table: not causal (Kramers-Kronig): no relaxing material has this E' and E''; the best causal fit misses "
      << (fit.worst_is_loss ? "E''" : "E'") << " at omega = " << fit.worst_omega << " rad/s by "
      << 100 * fit.max_misfit << " % (tolerance " << 100 * kCausalityTolerance << " %)";
    throw InputError(source, s.str());
  }
  return fit;
}

}  // namespace wr
