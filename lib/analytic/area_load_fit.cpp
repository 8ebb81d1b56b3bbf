#include "lib/analytic/area_load_fit.hpp"

#include <cmath>
#include <stdexcept>

#include "lib/core/least_squares.hpp"

namespace wr {
namespace {

void check_curve(const std::vector<double>& s, const std::vector<double>& a, std::size_t min_points) {
  if (s.size() != a.size()) throw std::invalid_argument("sigma* and A/A0 differ in length");
  if (s.size() < min_points) throw std::invalid_argument("too few load steps for the fit");
  for (std::size_t k = 0; k < s.size(); ++k)
    if (!(s[k] > 0) || !(a[k] >= 0 && a[k] <= 1)) throw std::invalid_argument("sigma* must be > 0 and A/A0 in [0, 1]");
}

}  // namespace

QuarticAreaFit fit_quartic_area(const std::vector<double>& s, const std::vector<double>& a) {
  check_curve(s, a, 4);
  // Least squares in the basis s, s^2, s^3, s^4 (scaled by the largest s for conditioning).
  double smax = 0;
  for (double v : s) smax = std::max(smax, v);
  Eigen::MatrixXd B(static_cast<Eigen::Index>(s.size()), 4);
  Eigen::VectorXd y(static_cast<Eigen::Index>(s.size()));
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double x = s[k] / smax;
    B.row(Eigen::Index(k)) << x, x * x, x * x * x, x * x * x * x;
    y(Eigen::Index(k)) = a[k];
  }
  const std::optional<Eigen::VectorXd> c = least_squares(B, y);
  if (!c) throw std::invalid_argument("the load steps do not determine a quartic (repeated sigma*)");
  QuarticAreaFit f;
  f.kappa = (*c)(0) / smax;
  f.lambda = (*c)(1) / (smax * smax);
  f.omega = (*c)(2) / (smax * smax * smax);
  f.pi = (*c)(3) / (smax * smax * smax * smax);
  double mean = 0, ss_tot = 0, ss_res = 0;
  for (double v : a) mean += v / double(a.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double x = s[k];
    const double model = ((f.pi * x + f.omega) * x + f.lambda) * x * x + f.kappa * x;
    ss_res += (a[k] - model) * (a[k] - model);
    ss_tot += (a[k] - mean) * (a[k] - mean);
  }
  f.r2 = ss_tot > 0 ? 1 - ss_res / ss_tot : 1.0;
  return f;
}

LowPressureKappa fit_low_pressure_kappa(const std::vector<double>& sigma_star, const std::vector<double>& area,
                                        double max_area) {
  check_curve(sigma_star, area, 0);
  if (!(max_area > 0 && max_area <= 1)) throw std::invalid_argument("the low-pressure limit of A/A0 must lie in (0, 1]");
  LowPressureKappa k;
  k.max_area = max_area;
  double sa = 0, ss = 0;
  for (std::size_t i = 0; i < area.size(); ++i)
    if (area[i] <= max_area) {
      sa += sigma_star[i] * area[i];
      ss += sigma_star[i] * sigma_star[i];
      ++k.points;
    }
  if (k.points > 0) k.kappa = sa / ss;
  return k;
}

double yam_area_fraction(double s, double kappa, double beta, double mu) {
  const double e = mu - 1;
  return std::pow(beta + std::pow(kappa * s, e), 1 / e);
}

YamFit fit_yam(const std::vector<double>& s, const std::vector<double>& a, double kappa) {
  check_curve(s, a, 2);
  if (!(kappa > 0)) throw std::invalid_argument("kappa must be > 0");
  auto cost = [&](double beta, double mu) {
    double c = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
      const double d = yam_area_fraction(s[k], kappa, beta, mu) - a[k];
      c += d * d;
    }
    return std::isfinite(c) ? c : INFINITY;
  };
  // Coarse-to-fine search: beta in (0, 4], mu in [-8, 0.95]; each round zooms on the best cell.
  double b_lo = 0.01, b_hi = 4, m_lo = -8, m_hi = 0.95, best_b = 1, best_m = 0, best = INFINITY;
  for (int round = 0; round < 12; ++round) {
    const int n = 24;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double b = b_lo + (b_hi - b_lo) * i / n, m = m_lo + (m_hi - m_lo) * j / n;
        const double c = cost(b, m);
        if (c < best) {
          best = c;
          best_b = b;
          best_m = m;
        }
      }
    const double db = (b_hi - b_lo) / n * 2, dm = (m_hi - m_lo) / n * 2;
    b_lo = std::max(1e-6, best_b - db);
    b_hi = best_b + db;
    m_lo = best_m - dm;
    m_hi = std::min(0.999, best_m + dm);
  }
  return {kappa, best_b, best_m, std::sqrt(best / double(s.size()))};
}

}  // namespace wr
