#include "lib/friction/flash_temperature.hpp"

#include <cmath>

#include "lib/core/errors.hpp"

namespace wr {

double erfcx(double x) {
  if (x < 26) return std::exp(x * x) * std::erfc(x);  // erfc(26) ~ 1e-295 is still a normal double
  // Asymptotic series (Abramowitz & Stegun 7.1.23); at x >= 26 the next term is below 1e-12.
  const double y = 1 / (2 * x * x);
  return (1 - y * (1 - 3 * y * (1 - 5 * y * (1 - 7 * y)))) / (x * std::sqrt(M_PI));
}

double flash_kernel(double b, double kappa, double diffusivity, double t) {
  const double s = std::sqrt(diffusivity * t);
  if (b * s < 1e-5 && kappa * s < 1e-5) return t;  // adiabatic: the closed form cancels here
  const double bracket = std::erfc(kappa * s) / kappa - std::exp(-kappa * kappa * s * s) * erfcx(b * s) / b;
  return (1 / (kappa * (b + kappa)) - b / (b * b - kappa * kappa) * bracket) / diffusivity;
}

FlashTemperature::FlashTemperature(const Compound& compound, double v, double pressure) : v_(v), pressure_(pressure) {
  if (!compound.thermal)
    throw InputError("--flash-temperature", "the compound \"" + compound.name +
                                                "\" has no \"thermal\" block (density, specific heat, conductivity)");
  rho_c_ = compound.thermal->density * compound.thermal->specific_heat;
  diffusivity_ = compound.thermal->conductivity / rho_c_;
}

double FlashTemperature::rise_density(double q, double dmu_dlnq_over_p) const {
  // Q dq' = sigma0 v q (dmu/P) per unit volume; per unit ln q the source is q times that / q.
  const double source = pressure_ * v_ * q * dmu_dlnq_over_p;  // W/m^3 per unit ln q
  const double d = M_PI / q;
  return source * flash_kernel(q, 2 / d, diffusivity_, d / v_) / rho_c_;
}

}  // namespace wr
