#pragma once
// Persson's hysteresis friction of rubber sliding at speed v on a rigid, isotropic rough surface
// (B.N.J. Persson, J. Chem. Phys. 115, 3840 (2001); the thesis's eq. 3.170; the viscoelastic
// contact area of Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), eq. 30-31):
//
//   mu(v) = 1/2 int_{qs}^{q1} dq q^3 C(q) P(q) int_0^{2pi} dphi cos(phi) Im E(q v cos phi, T_q) / E0
//   P(q)  = erf(1 / (2 sqrt(G(q)))),
//   G(q)  = 1/8 int_{qs}^{q} dq' q'^3 C(q') int_0^{2pi} dphi |E(q' v cos phi, T_q')|^2 / E0^2,
//   E0    = (1 - nu^2) sigma0.
//
// The angle integrals are exact for a Prony series (derivation in docs/friction-model.md):
// with a = omega tau aT and r(a) = 1/sqrt(1+a^2),
//   int cos(phi) Im E(omega cos phi) dphi = 2 pi sum_i dE_i a_i r_i / (1 + sqrt(1 + a_i^2))
//   int |E(omega cos phi)|^2 dphi = 2 pi [Eg^2 - 2 Eg sum_i dE_i r_i
//                                         + 2 sum_ij dE_i dE_j a_i r_i / (a_i + a_j)],
// so there is no angle quadrature (a table compound is used through its causal Prony fit,
// lib/friction/modulus_table). The q integrals use nodes uniform in ln q
// (`points_per_decade`) and the cumulative rule of the quadratic through three neighbouring
// nodes (third order): G at every node and mu at the end come from the same rule, so a test can
// show convergence in the node count.
//
// Flash temperature (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)): see
// lib/friction/flash_temperature.hpp; off, T_q = T0 at every scale (the isothermal theory).
//
// Units: SI (m, 1/m, m^4 for C, Pa, m/s), temperatures in deg C.
#include <string>
#include <vector>

#include "lib/friction/compound.hpp"
#include "lib/friction/roughness_spectrum.hpp"

namespace wr {

struct FrictionOptions {
  double pressure = 0.3e6;      // sigma0, Pa, > 0
  double temperature = 20;      // T0, deg C (road and rubber far from the contact)
  int points_per_decade = 48;   // q nodes per decade of q1 / qs
  bool flash_temperature = false;
  int threads = 0;              // over speeds; 0 = hardware
};

struct FrictionPoint {
  double v = 0;                // m/s
  double mu = 0;               // hysteresis friction coefficient
  double area_fraction = 0;    // P(q1): A/A0 at the finest scale
  double temperature_rise = 0; // K, the flash temperature's rise at q1 (0 when off)
  double mu_extrapolated = 0;  // the part of mu from q above the measured band
};

// Throws InputError naming the option: pressure <= 0, points_per_decade < 4, a temperature at
// or below the WLF pole, a speed <= 0 or not finite.
void check_friction_options(const FrictionOptions& opt, const Compound& compound);

// mu at one speed (> 0, m/s).
FrictionPoint hysteresis_friction(const RoughnessSpectrum& psd, const Compound& compound, double v,
                                  const FrictionOptions& opt);
// mu at each speed, speeds computed in parallel; results in the order of `speeds`.
std::vector<FrictionPoint> friction_curve(const RoughnessSpectrum& psd, const Compound& compound,
                                          const std::vector<double>& speeds, const FrictionOptions& opt);

// The two angle integrals at omega (rad/s) with the compound's relaxation times multiplied by
// `shift` (aT): the loss integral int cos(phi) Im E dphi and the power integral
// int |E|^2 dphi over [0, 2 pi], Pa and Pa^2. Exposed for the tests.
struct AngleIntegrals {
  double loss = 0, power = 0;
};
AngleIntegrals angle_integrals(const Compound& compound, double omega, double shift);

}  // namespace wr
