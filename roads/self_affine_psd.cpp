#include "roads/self_affine_psd.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wr {

SelfAffinePsd SelfAffinePsd::from_eq44(double h0, double hurst, double qL, double q0, double q1,
                                       double q1_fraction) {
  SelfAffinePsd p;
  p.h0 = h0;
  p.hurst = hurst;
  p.qL = qL;
  p.q0 = q0;
  p.q1 = q1;
  p.q1_cut = q1 * q1_fraction;
  // eq. 4.4
  const double bracket = (1.0 - qL * qL / (q0 * q0)) + (1.0 / hurst) * (1.0 - std::pow(q0 / q1, 2 * hurst));
  p.k = (h0 / q0) * (h0 / q0) / (std::numbers::pi * bracket);
  return p;
}

double SelfAffinePsd::operator()(double q) const {
  if (q < qL * (1 - 1e-12) || q > q1_cut * (1 + 1e-12)) return 0.0;
  if (q < q0) return k;
  return k * std::pow(q / q0, -2.0 * (hurst + 1.0));
}

double SelfAffinePsd::radial_integral(int n) const {
  // Plateau part on [qL, min(q0, q1_cut)], power-law part on [q0, q1_cut].
  const double top = q1_cut;
  double s = 0;
  const double a = qL, b = std::min(q0, top);
  if (b > a) s += k * (std::pow(b, n + 1) - std::pow(a, n + 1)) / (n + 1);
  if (top > q0) {
    const double e = n + 1 - 2.0 * (hurst + 1.0);  // exponent after integration
    const double scale = k * std::pow(q0, 2.0 * (hurst + 1.0));
    if (std::abs(e) < 1e-14)
      s += scale * std::log(top / q0);
    else
      s += scale * (std::pow(top, e) - std::pow(q0, e)) / e;
  }
  return s;
}

double SelfAffinePsd::m0() const { return 2 * std::numbers::pi * radial_integral(1); }
double SelfAffinePsd::m2() const { return std::numbers::pi * radial_integral(3); }
double SelfAffinePsd::m4() const { return 0.75 * std::numbers::pi * radial_integral(5); }
double SelfAffinePsd::rms_slope() const { return std::sqrt(2 * m2()); }
double SelfAffinePsd::rms_height() const { return std::sqrt(m0()); }

}  // namespace wr
