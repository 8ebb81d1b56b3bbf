#pragma once
// The area-load curve of a contact run and its fits, in one place for every command: the
// converged normal steps (sigma* > 0), the low-pressure kappa (sec. 5.2.3), the thesis's quartic
// (eq. 5.4) and the YAM law (eq. 3.179, with the quartic's kappa) (lib/analytic/area_load_fit).
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/analytic/area_load_fit.hpp"
#include "lib/contact/contact_step.hpp"

namespace wr {

struct NormalCurve {
  std::vector<double> sigma_star, area;
};
// The converged steps of the normal phase (ux = 0) with sigma* > 0.
NormalCurve normal_curve(const std::vector<ContactStep>& steps);

struct AreaLoadFits {
  bool any = false;                       // a converged normal step exists
  LowPressureKappa low;                   // from any number of steps
  std::optional<QuarticAreaFit> quartic;  // four or more steps, a regular fit
  std::optional<YamFit> yam;              // with a positive quartic kappa
};
AreaLoadFits area_load_fits(const std::vector<ContactStep>& steps);

// {low_pressure {kappa, points, max_area_fraction[, kappa_central_slope]}, quartic {Pi, Omega,
// Lambda, kappa, r2, eps_1e4}, yam {kappa, beta, mu, rms_error}}; null without a converged normal
// step. `central_ratio` > 0 (central- over forward-difference rms slope of the obstacle) adds
// kappa with sigma* normalised by the central slope (kappa scales with the slope dividing sigma*).
nlohmann::json area_load_fits_json(const AreaLoadFits& f, double central_ratio = 0);
// {Pi, Omega, Lambda, kappa, r2}: the quartic as the roughness sweep records it.
nlohmann::json quartic_json(const QuarticAreaFit& q);

}  // namespace wr
