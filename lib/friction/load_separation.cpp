#include "lib/friction/load_separation.hpp"

#include <cmath>
#include <deque>
#include <stdexcept>

#include "lib/friction/hysteresis_friction.hpp"

namespace wr {
namespace {

// F(x) on nodes uniform in ln x over [kLow, kHigh], integrated from the top by the trapezoid
// rule in ln x (the integrand in ln x, [gamma + 3 (1-gamma) erf^2 x] e^{-x^2}, is smooth and
// bounded), 8000 nodes, Simpson's rule on each interval; between nodes a cubic Hermite
// interpolant (below 1e-8 relative, tests).
constexpr double kLow = 1e-12, kHigh = 7.0;
constexpr int kNodes = 8000;

double integrand(double g, double x) {
  const double e = std::erf(x);
  return (g + 3 * (1 - g) * e * e) * std::exp(-x * x);
}

struct KernelTable {
  double gamma = -1;
  std::vector<double> F, f;  // F and the integrand in ln x (F' = -f) at the nodes
  double h = 0;
  explicit KernelTable(double g) : gamma(g), F(kNodes, 0.0), f(kNodes, 0.0) {
    h = std::log(kHigh / kLow) / (kNodes - 1);
    for (int k = 0; k < kNodes; ++k) f[k] = integrand(g, kLow * std::exp(k * h));
    for (int k = kNodes - 2; k >= 0; --k) {
      const double a = kLow * std::exp(k * h), b = kLow * std::exp((k + 1) * h);
      F[k] = F[k + 1] + h / 6 * (f[k] + 4 * integrand(g, std::sqrt(a * b)) + f[k + 1]);  // Simpson in ln x
    }
  }
  // Cubic Hermite in ln x between nodes from F and F' = -f: error O(h^4), no erf at run time.
  double operator()(double x) const {
    if (x >= kHigh) return 0.0;
    if (x <= kLow) return F[0] + gamma * std::log(kLow / x);  // erf^2 x ~ 0 below kLow
    const double t = std::log(x / kLow) / h;
    const int k = std::min(static_cast<int>(t), kNodes - 2);
    const double r = t - k, r2 = r * r, r3 = r2 * r;
    const double h00 = 2 * r3 - 3 * r2 + 1, h10 = r3 - 2 * r2 + r, h01 = -2 * r3 + 3 * r2, h11 = r3 - r2;
    return h00 * F[k] - h10 * h * f[k] + h01 * F[k + 1] - h11 * h * f[k + 1];
  }
};

const KernelTable& kernel(double gamma) {
  // One table per gamma value asked for in this thread (normally one, kLoadSeparationGamma).
  thread_local std::deque<KernelTable> tables;  // a deque keeps earlier references valid
  for (const KernelTable& t : tables)
    if (t.gamma == gamma) return t;
  tables.emplace_back(gamma);
  return tables.back();
}

}  // namespace

double load_separation_kernel(double x0, double gamma) { return kernel(gamma)(x0); }

LoadSeparation::LoadSeparation(const RoughnessSpectrum& psd, const Compound& compound, double v, double temperature,
                               int points_per_decade, double gamma)
    : gamma_(gamma) {
  if (!(v > 0) || points_per_decade < 4 || !(psd.q_end > psd.q_start && psd.q_start > 0) || !(gamma > 0 && gamma <= 1))
    throw std::invalid_argument("LoadSeparation: v > 0, a spectrum band and gamma in (0, 1] required");
  const double a = std::log(psd.q_start), b = std::log(psd.q_end);
  const int n = std::max(8, static_cast<int>(std::ceil(points_per_decade * (b - a) / std::log(10.0)))) + 1;
  const double h = (b - a) / (n - 1);
  const double shift = std::pow(10.0, compound.log10_shift(temperature));
  const double one_nu2 = 1 - compound.poisson * compound.poisson;
  double m2 = 0, g = 0, h2 = 0;  // running int q^3 C dq, g(q), int 2 pi q C dq
  double prev_m = 0, prev_g = 0, prev_h = 0;
  for (int k = 0; k < n; ++k) {
    // the ends exactly: a band's C may stop at q_end
    const double q = k == 0 ? psd.q_start : (k == n - 1 ? psd.q_end : std::exp(a + k * h)), c = psd(q);
    const AngleIntegrals ai = angle_integrals(compound, q * v, shift);
    // integrands in ln q (dq = q d ln q), trapezoid
    const double im = q * q * q * q * c, ig = im * ai.power / (8 * one_nu2 * one_nu2), ih = 2 * M_PI * q * q * c;
    if (k > 0) {
      m2 += 0.5 * h * (prev_m + im);
      g += 0.5 * h * (prev_g + ig);
      h2 += 0.5 * h * (prev_h + ih);
    }
    prev_m = im, prev_g = ig, prev_h = ih;
    if (k == 0) continue;  // w and s are infinite at q0: the node carries no weight
    const double w = 1 / std::sqrt(M_PI * m2);
    const double wk = (k == n - 1 ? 0.5 : 1.0) * h;
    weight_.push_back(std::sqrt(M_PI) * q * q * q * c * w * wk);
    s_.push_back(1 / (2 * std::sqrt(g)));
  }
  s_end_ = s_.back();
  rms_ = std::sqrt(h2);
}

double LoadSeparation::separation(double pressure) const {
  const KernelTable& F = kernel(gamma_);
  double u = 0;
  for (std::size_t k = 0; k < s_.size(); ++k) u += weight_[k] * F(s_[k] * pressure);
  return u;
}

double LoadSeparation::contact_fraction(double pressure) const { return std::erf(s_end_ * pressure); }

double LoadSeparation::pressure_at(double u) const {
  double lo = std::log(1e-30), hi = std::log(1e30);
  if (separation(std::exp(lo)) <= u) return 0.0;
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (separation(std::exp(mid)) > u ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

}  // namespace wr
