#pragma once
// Fits of the contact-area / load curve A/A0 (sigma*) of normal-load experiments.
//
// - The thesis's quartic without constant term (eq. 5.4):
//     A/A0 = Pi s^4 + Omega s^3 + Lambda s^2 + kappa s,   s = sigma*,
//   by linear least squares, with R^2 (Tables C.1-C.9 report eps = 1 - R^2). kappa is the
//   low-pressure slope of eq. 3.169.
// - The YAM law (eq. 3.179): A/A0 = [beta + (kappa s)^(mu - 1)]^(1 / (mu - 1)), mu < 1, which
//   tends to kappa s at low pressure and to beta^(1/(mu-1)) at high pressure. Fitted as the
//   thesis describes [YAM14]: kappa first (here: given, e.g. from the quartic), then beta and mu
//   by non-linear least squares (a deterministic coarse-to-fine search over (beta, mu)).
// Inputs: sigma* > 0 and A/A0 in [0, 1], equal lengths. Throws std::invalid_argument otherwise
// or with too few points (4 for the quartic, 2 for YAM).
#include <cstddef>
#include <vector>

namespace wr {

struct QuarticAreaFit {
  double pi = 0, omega = 0, lambda = 0, kappa = 0;
  double r2 = 0;  // coefficient of determination of the fit
};
QuarticAreaFit fit_quartic_area(const std::vector<double>& sigma_star, const std::vector<double>& area);

// The thesis's low-pressure kappa (sec. 5.2.3, Fig. 5.6-5.7): the linear law A/A0 = kappa s of
// eq. 3.169 fitted by least squares through the origin to the points with A/A0 <= max_area
// (the thesis: A below 15 % of A0), kappa = sum(s a) / sum(s^2). `points` says how many were
// used; kappa is 0 with none. Validated inputs as above (no minimum count).
struct LowPressureKappa {
  double kappa = 0;
  std::size_t points = 0;
  double max_area = 0.15;
};
LowPressureKappa fit_low_pressure_kappa(const std::vector<double>& sigma_star, const std::vector<double>& area,
                                        double max_area = 0.15);

double yam_area_fraction(double sigma_star, double kappa, double beta, double mu);

struct YamFit {
  double kappa = 0, beta = 0, mu = 0;
  double rms_error = 0;  // of A/A0
};
YamFit fit_yam(const std::vector<double>& sigma_star, const std::vector<double>& area, double kappa);

}  // namespace wr
