#include "lib/analytic/nayak_summits.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wr {

double nayak_summit_pdf(double xi, double alpha) {
  const double a = alpha;
  const double c1 = a / (2 * a - 3);                                            // eq. 3.64
  const double beta = std::sqrt(3.0 / (2 * (2 * a - 3))) * xi;                  // eq. 3.73
  const double gamma = std::sqrt(a / (2 * (a - 1) * (2 * a - 3))) * xi;         // eq. 3.74
  const double s2pi = std::sqrt(2 * std::numbers::pi);
  const double pi1 = std::exp(-c1 * xi * xi) * std::sqrt(3 * (2 * a - 3) / (a * a)) * xi;  // 3.70
  const double pi2 = 3 * s2pi / (2 * a) * std::exp(-0.5 * xi * xi) * (1 + std::erf(beta)) *
                     (xi * xi - 1);                                                       // 3.71
  const double pi3 = s2pi * std::sqrt(a / (3 * (a - 1))) *
                     std::exp(-a * xi * xi / (2 * (a - 1))) * (1 + std::erf(gamma));       // 3.72
  return std::sqrt(3.0) / (2 * std::numbers::pi) * (pi1 + pi2 + pi3);
}

double nayak_summit_density(double m2, double m4) {
  return m4 / (6 * std::numbers::pi * std::sqrt(3.0) * m2);
}

SummitMoments nayak_summit_moments(double alpha) {
  const int n = 24000;
  const double lo = -12, hi = 12, h = (hi - lo) / n;
  double s0 = 0, s1 = 0, s2 = 0;
  for (int i = 0; i <= n; ++i) {
    const double x = lo + i * h;
    const double w = (i == 0 || i == n) ? 0.5 * h : h;
    const double p = nayak_summit_pdf(x, alpha);
    s0 += w * p;
    s1 += w * p * x;
    s2 += w * p * x * x;
  }
  const double mean = s1 / s0;
  return {mean, s2 / s0 - mean * mean};
}

SummitMoments greenwood_summit_moments(double alpha) {
  return {4.0 / std::sqrt(std::numbers::pi * alpha), 1.0 - 0.8968 / alpha};
}

NayakSummitCdf::NayakSummitCdf(double alpha) {
  const int n = 24000;
  step_ = (hi_ - lo_) / n;
  cdf_.resize(n + 1);
  cdf_[0] = 0;
  double prev = nayak_summit_pdf(lo_, alpha);
  for (int i = 1; i <= n; ++i) {
    const double p = nayak_summit_pdf(lo_ + i * step_, alpha);
    cdf_[i] = cdf_[i - 1] + 0.5 * step_ * (prev + p);
    prev = p;
  }
  const double total = cdf_.back();
  for (double& c : cdf_) c /= total;
}

double NayakSummitCdf::operator()(double xi) const {
  if (xi <= lo_) return 0.0;
  if (xi >= hi_) return 1.0;
  const double t = (xi - lo_) / step_;
  const std::size_t i = std::min(static_cast<std::size_t>(t), cdf_.size() - 2);
  const double f = t - static_cast<double>(i);
  return cdf_[i] + f * (cdf_[i + 1] - cdf_[i]);
}

double ks_distance_to_nayak(std::vector<double> xi, double alpha) {
  if (xi.empty() || !(alpha > 1.5)) return std::nan("");
  std::sort(xi.begin(), xi.end());
  const NayakSummitCdf cdf(alpha);
  const double n = static_cast<double>(xi.size());
  double d = 0;
  for (std::size_t i = 0; i < xi.size(); ++i) {
    const double f = cdf(xi[i]);
    d = std::max({d, std::abs(f - i / n), std::abs((i + 1) / n - f)});
  }
  return d;
}

}  // namespace wr
