#include "lib/analytic/contact_theory.hpp"

#include <cmath>
#include <numbers>

namespace wr {

double kappa_persson() { return std::sqrt(8.0 / std::numbers::pi); }
double kappa_bgt() { return std::sqrt(2.0 * std::numbers::pi); }

double persson_area_fraction(double sigma_star) {
  // G = (E*/sigma0)^2 m2 / 4 (eq. 3.163), A/A0 = erf(1 / (2 sqrt G)) = erf(sigma0 / (E* sqrt m2))
  // and sqrt(m2) = rms_slope / sqrt 2, so the argument is sqrt(2) sigma*.
  return std::erf(std::sqrt(2.0) * sigma_star);
}

}  // namespace wr
