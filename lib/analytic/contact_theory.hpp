#pragma once
// Analytic rough-contact predictions at low pressure (thesis sec. 3.3-3.4, 5.2).
//
// sigma_star is the normalised pressure sigma0 / (E* sqrt(<|grad h|^2>)) of eq. 5.2
// (dimensionless, >= 0); areas are fractions A/A0 in [0, 1].
namespace wr {

// Low-pressure slope kappa in A/A0 = kappa sigma* (eq. 3.169).
double kappa_persson();  // sqrt(8/pi) ~ 1.596 (eq. 3.165)
double kappa_bgt();      // sqrt(2 pi) ~ 2.507 (eq. 3.166)

// Persson's contact area, erf form (eq. 3.162 rewritten with eq. 3.163 and 3.168):
// A/A0 = erf(sqrt(2) sigma*). Tends to kappa_persson() sigma* as sigma* -> 0.
double persson_area_fraction(double sigma_star);

}  // namespace wr
