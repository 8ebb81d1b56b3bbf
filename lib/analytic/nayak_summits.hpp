#pragma once
// Nayak's statistics of summits (local maxima) of an isotropic Gaussian surface (thesis 3.1.3).
//
// alpha = m0 m4 / m2^2 >= 1.5 (eq. 3.63); xi = summit height / h0 (eq. 3.61).
#include <vector>

namespace wr {

// Summit-height probability density p_sum(xi; alpha), eq. 3.69-3.74. Requires alpha > 1.5.
double nayak_summit_pdf(double xi, double alpha);

// Summits per unit area, eq. 3.67: m4 / (6 pi sqrt(3) m2), 1/m^2 for m2 [-], m4 [1/m^2].
double nayak_summit_density(double m2, double m4);

struct SummitMoments {
  double mean = 0;      // of xi
  double variance = 0;  // of xi
};

// Mean and variance of xi by integrating eq. 3.69 numerically (trapezoid on [-12, 12],
// 24000 intervals: the integrand is smooth and decays as a Gaussian, error < 1e-9).
SummitMoments nayak_summit_moments(double alpha);

// Greenwood's closed forms, eq. 4.5: mean = 4 / sqrt(pi alpha), variance = 1 - 0.8968/alpha.
// (The thesis prints the mean as 4/(pi alpha); integrating eq. 3.69 gives 4/sqrt(pi alpha),
// which is Greenwood's (1984) result and what this function returns.)
SummitMoments greenwood_summit_moments(double alpha);

// Cumulative distribution q_sum(xi) (eq. 3.78) tabulated for fast lookup.
class NayakSummitCdf {
 public:
  explicit NayakSummitCdf(double alpha);
  double operator()(double xi) const;  // linear interpolation in the table, clamped to [0, 1]

 private:
  double lo_ = -12, hi_ = 12, step_ = 0;
  std::vector<double> cdf_;
};

// Kolmogorov-Smirnov distance between the empirical CDF of `xi` and q_sum(.; alpha).
double ks_distance_to_nayak(std::vector<double> xi, double alpha);

}  // namespace wr
