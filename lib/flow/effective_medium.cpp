#include "lib/flow/effective_medium.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace wr {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kPi = 3.14159265358979323846;

// Mean of |N(m, h^2)| (the folded normal).
double folded_mean(double m, double h) {
  if (h <= 0) return std::fabs(m);
  return h * std::sqrt(2 / kPi) * std::exp(-m * m / (2 * h * h)) + m * std::erf(m / (kSqrt2 * h));
}

// Nodes and weights of the free-gap distribution: x = m + h z over z in [-6, 6] (midpoint rule
// on 241 cells: on a Gaussian weight it converges faster than any power of the cell; the
// integrand is bounded, so the tails beyond 6 sigma weigh < 2e-9), folded.
struct Nodes {
  std::vector<double> u, w;
};

Nodes free_gap_nodes(double m, double h) {
  Nodes n;
  if (h <= 0) {
    n.u = {std::fabs(m)};
    n.w = {1.0};
    return n;
  }
  constexpr int kCells = 241;
  constexpr double kSpan = 6;
  const double dz = 2 * kSpan / kCells;
  double total = 0;
  for (int i = 0; i < kCells; ++i) {
    const double z = -kSpan + (i + 0.5) * dz;
    const double w = std::exp(-0.5 * z * z);
    n.u.push_back(std::fabs(m + h * z));
    n.w.push_back(w);
    total += w;
  }
  for (double& w : n.w) w /= total;
  return n;
}

}  // namespace

double effective_medium_conductance(const GapStatistics& s, double critical_contact) {
  const double A = s.contact_fraction;
  if (!(A >= 0 && A <= 1) || !(s.mean_gap >= 0) || !(s.rms_height >= 0) || !std::isfinite(s.mean_gap) ||
      !std::isfinite(s.rms_height))
    throw std::invalid_argument("effective_medium_conductance: contact fraction in [0,1], gap and rms >= 0");
  if (!(critical_contact > 0 && critical_contact < 1))
    throw std::invalid_argument("effective_medium_conductance: critical contact fraction in (0, 1)");
  if (A >= critical_contact || s.mean_gap == 0) return 0.0;
  const double free_mean = s.mean_gap / (1 - A);  // mean of the free gaps
  // The free gaps' centre m: folded_mean(m, h) = free_mean. It is increasing in m >= 0 from
  // h sqrt(2/pi); below that the spread is too wide for the mean, and h shrinks to fit at m = 0.
  double h = s.rms_height, m = 0;
  if (folded_mean(0, h) >= free_mean) {
    h = free_mean / std::sqrt(2 / kPi);
  } else {
    double lo = 0, hi = free_mean;  // folded_mean(free_mean, h) >= free_mean
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (folded_mean(mid, h) < free_mean ? lo : hi) = mid;
    }
    m = 0.5 * (lo + hi);
  }
  const Nodes n = free_gap_nodes(m, h);
  std::vector<double> sigma(n.u.size());
  double smax = 0;
  for (std::size_t i = 0; i < n.u.size(); ++i) smax = std::max(smax, sigma[i] = n.u[i] * n.u[i] * n.u[i] / 12);
  const double a = critical_contact / (1 - critical_contact);
  // Residual of the self-consistency; decreasing in K from (1 - A) - A / a > 0 at K = 0+ to
  // -A/a - (1 - A)/a < 0 as K -> inf, so the root is bracketed by (0, smax].
  auto residual = [&](double K) {
    double r = -A / a;
    for (std::size_t i = 0; i < sigma.size(); ++i) r += (1 - A) * n.w[i] * (sigma[i] - K) / (sigma[i] + a * K);
    return r;
  };
  // The root lies in (0, smax]; K / smax below 1e-30 is zero for any flow that matters.
  // Regula falsi with the Illinois modification in ln K (superlinear, keeps the bracket).
  double lo = std::log(smax * 1e-30), hi = std::log(smax);
  double f_hi = residual(smax);
  if (f_hi >= 0) return smax;
  double f_lo = residual(std::exp(lo));
  if (f_lo <= 0) return 0.0;
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    double mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    const double f = residual(std::exp(mid));
    if (f > 0) {
      lo = mid, f_lo = f;
      if (side == 1) f_hi *= 0.5;
      side = 1;
    } else {
      hi = mid, f_hi = f;
      if (side == -1) f_lo *= 0.5;
      side = -1;
    }
    if (f == 0) return std::exp(mid);
  }
  return std::exp(0.5 * (lo + hi));
}

}  // namespace wr
