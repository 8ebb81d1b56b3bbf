// What `wetroad contact` prints and records per run: the step rows, the step JSON, the curve's
// summaries (static friction, area-load fits).
#include "app/contact_output.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "lib/analytic/area_load_fit.hpp"
#include "roads/height_stats.hpp"

namespace wr::app {

// The area-load fits over the converged normal steps: the low-pressure kappa (sec. 5.2.3) from
// any of them, the quartic (eq. 5.4) and YAM (eq. 3.179, with the quartic's kappa) from four or
// more; null without a converged normal step. `central_ratio` > 0 (central- over forward-difference
// rms slope of the obstacle) adds the low-pressure kappa with sigma* normalised by the central
// slope: kappa scales with the slope that divides sigma*, and thesis-era codes took gradient().
nlohmann::json area_load_fit_json(const std::vector<ContactStep>& steps, bool talk, double central_ratio) {
  std::vector<double> s, a;
  for (const auto& st : steps)
    if (st.converged && st.ux == 0 && st.sigma_star > 0) {
      s.push_back(st.sigma_star);
      a.push_back(st.area_fraction);
    }
  if (s.empty()) return nullptr;
  // The low-pressure regression of sec. 5.2.3 needs no minimum: any step below 15 % counts.
  const LowPressureKappa lp = fit_low_pressure_kappa(s, a);
  nlohmann::json low = {{"kappa", lp.kappa}, {"points", lp.points}, {"max_area_fraction", lp.max_area}};
  if (central_ratio > 0) low["kappa_central_slope"] = lp.kappa * central_ratio;
  if (talk && lp.points > 0) {
    std::printf("  low-pressure kappa (sec. 5.2.3, A/A0 <= %.2f, %zu step%s): %.4f", lp.max_area, lp.points,
                lp.points == 1 ? "" : "s", lp.kappa);
    if (central_ratio > 0) std::printf(" (%.4f with sigma* over the central-difference slope)", lp.kappa * central_ratio);
    std::printf("\n");
  }
  if (s.size() < 4) return nlohmann::json{{"low_pressure", low}};
  try {
    const QuarticAreaFit q = fit_quartic_area(s, a);
    nlohmann::json j = {{"quartic", {{"Pi", q.pi}, {"Omega", q.omega}, {"Lambda", q.lambda}, {"kappa", q.kappa},
                                     {"r2", q.r2}, {"eps_1e4", 1e4 * (1 - q.r2)}}},
                        {"low_pressure", low}};
    if (q.kappa > 0) {
      const YamFit y = fit_yam(s, a, q.kappa);
      j["yam"] = {{"kappa", y.kappa}, {"beta", y.beta}, {"mu", y.mu}, {"rms_error", y.rms_error}};
    }
    if (talk)
      std::printf("  area-load fit (eq. 5.4): kappa %.4f, Lambda %.4g, Omega %.4g, Pi %.4g, 1 - R^2 = %.2e\n", q.kappa,
                  q.lambda, q.omega, q.pi, 1 - q.r2);
    return j;
  } catch (const std::invalid_argument&) {
    return nlohmann::json{{"low_pressure", low}};
  }
}

// The curve's summaries in the JSON: the shear test's peak (static friction) and the area-load
// fits of the normal steps. Returns the peak step (nullptr without one).
// `obstacle` is the surface whose forward-difference slope (j["rms_slope"]) normalised sigma*.
const ContactStep* add_curve_summaries(nlohmann::json& j, const std::vector<ContactStep>& steps, bool talk,
                                       const HeightMap& obstacle) {
  const ContactStep* peak = peak_friction(steps);
  if (peak)
    j["peak"] = {{"mu", peak->mu}, {"ux", peak->ux}, {"step", int(peak - steps.data()) + 1}, {"reached", peak_reached(steps)}};
  const double central = rms_slope_finite_difference(obstacle, 0, SlopeStencil::central);
  j["rms_slope_central"] = central;
  j["area_load_fit"] = area_load_fit_json(steps, talk, central / j["rms_slope"].get<double>());
  return peak;
}

void print_peak(const ContactStep* peak, const std::vector<ContactStep>& steps) {
  if (!peak) return;
  if (peak_reached(steps))
    std::printf("  static friction (peak mu of the shear steps): mu = %.4g at ux = %.4g m (step %d)\n", peak->mu,
                peak->ux, int(peak - steps.data()) + 1);
  else
    std::printf("  static friction: mu >= %.4g (still rising at ux = %.4g m, step %d: the peak lies beyond --ux)\n",
                peak->mu, peak->ux, int(peak - steps.data()) + 1);
}

void print_step_header() {
  std::printf("  %4s %10s %10s %11s %11s %8s %8s %9s %10s %10s %5s %6s %8s\n", "step", "uz [m]", "ux [m]", "Fz [N]",
              "Fx [N]", "mu", "A/A0", "sigma*", "sep [m]", "pen [m]", "sig", "lin", "wall [s]");
  std::fflush(stdout);
}

void print_step_row(int k, const ContactStep& st) {
  std::printf("  %4d %10.4g %10.4g %11.4e %11.4e %8.4f %8.4f %9.4g %10.3e %10.2e %5d %6d %8.2f%s\n", k, st.uz, st.ux,
              st.fz, st.fx, st.mu, st.area_fraction, st.sigma_star, st.separation, st.max_penetration,
              st.signorini_iterations, st.linear_iterations, st.wall_s,
              !st.converged ? "  FAILED" : st.failed_attempts > 0 ? "  (cut back)" : "");
  std::fflush(stdout);
}

}  // namespace wr::app
