#pragma once
// Persson's relation between the load the asperities carry and the mean interfacial separation
// of rubber on a rough road: the mean-field p_c(u) and A(u) of the squeeze-out model
// (lib/friction/squeeze_out.hpp), from the road's spectrum and the compound, in milliseconds.
//
// Theory (Persson, Phys. Rev. Lett. 99, 125502 (2007); Yang & Persson, Phys. Rev. Lett. 100,
// 024303 (2008), eq. 2-3): at nominal pressure p the mean separation is
//   u(p) = sqrt(pi) int_{q0}^{q1} dq q^2 C(q) w(q) int_p^inf (dp'/p') [gamma + 3 (1 - gamma) P^2(q, p')]
//          exp(-(s(q) p')^2),
//   w(q) = (pi int_{q0}^{q} dq' q'^3 C(q'))^(-1/2),   P(q, p) = erf(s(q) p),
// with s(q) = w(q) / E* for an elastic solid. The rubber sliding at v is excited at q v cos phi
// and is stiffer there: s(q) = 1 / (2 sqrt(g(q))), g(q) = G(q) p^2 of the friction model
// (lib/friction/hysteresis_friction.hpp: G = 1/8 int q^3 C int |E(q v cos phi)|^2 dphi / ((1-nu^2) p)^2),
// so that A/A0 = P(q1, p) is the hysteresis model's contact area at that speed and pressure.
// gamma ~ 0.4-0.5 corrects the elastic energy stored where contact is made (Yang & Persson
// fit gamma = 0.45 to numerical contact mechanics); kLoadSeparationGamma.
// The inner integral, in x = s p', is F(x0) = int_{x0}^inf (dx / x) [gamma + 3 (1 - gamma) erf^2 x] e^{-x^2},
// tabulated once; F ~ gamma ln(1/x0) as x0 -> 0, which gives the exponential load-separation
// law p ~ exp(-u / (gamma h)) of separated surfaces.
// Units: SI (m, Pa, m/s, deg C). The flash temperature is not applied (T0 at every scale).
#include <vector>

#include "lib/friction/compound.hpp"
#include "lib/friction/roughness_spectrum.hpp"

namespace wr {

constexpr double kLoadSeparationGamma = 0.45;

class LoadSeparation {
 public:
  // Spectrum C(q) on [q_start, q_end], the compound at `temperature` (deg C) sliding at v > 0
  // (m/s); `points_per_decade` >= 4 q nodes per decade.
  LoadSeparation(const RoughnessSpectrum& psd, const Compound& compound, double v, double temperature,
                 int points_per_decade = 48, double gamma = kLoadSeparationGamma);

  double separation(double pressure) const;        // u(p), m; p > 0 Pa; decreasing in p
  double contact_fraction(double pressure) const;  // P(q1, p) in [0, 1]
  // p with separation(p) = u, Pa: bisection in ln p on [1e-30, 1e30] Pa (0 when u exceeds
  // separation(1e-30 Pa)).
  double pressure_at(double separation) const;
  double rms_height() const { return rms_; }       // m, of the spectrum on [q_start, q_end]

 private:
  std::vector<double> weight_;  // sqrt(pi) q^2 C w dq at each node
  std::vector<double> s_;       // s(q), 1/Pa
  double s_end_ = 0, gamma_ = kLoadSeparationGamma, rms_ = 0;
};

// F(x0) above, for the tests.
double load_separation_kernel(double x0, double gamma);

}  // namespace wr
