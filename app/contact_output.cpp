// What `wetroad contact` prints and records per run: the step rows, the step JSON, the curve's
// summaries (static friction, area-load fits).
#include "app/contact_output.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "lib/contact/area_load_fits.hpp"
#include "lib/core/number_text.hpp"
#include "roads/height_stats.hpp"

namespace wr::app {

// The area-load fits (lib/contact/area_load_fits) as JSON, printed when `talk`.
nlohmann::json area_load_fit_json(const std::vector<ContactStep>& steps, bool talk, double central_ratio) {
  const AreaLoadFits f = area_load_fits(steps);
  if (talk && f.any && f.low.points > 0) {
    std::printf("  low-pressure kappa (sec. 5.2.3, A/A0 <= %.2f, %zu step%s): %.4f", f.low.max_area, f.low.points,
                f.low.points == 1 ? "" : "s", f.low.kappa);
    if (central_ratio > 0) std::printf(" (%.4f with sigma* over the central-difference slope)", f.low.kappa * central_ratio);
    std::printf("\n");
  }
  if (talk && f.quartic)
    std::printf("  area-load fit (eq. 5.4): kappa %.4f, Lambda %.4g, Omega %.4g, Pi %.4g, 1 - R^2 = %.2e\n", f.quartic->kappa,
                f.quartic->lambda, f.quartic->omega, f.quartic->pi, 1 - f.quartic->r2);
  return area_load_fits_json(f, central_ratio);
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
  if (!peak) {
    for (const ContactStep& st : steps)
      if (st.converged && st.ux != 0) {
        std::printf("  static friction: none: the block lost contact in the shear phase (A/A0 = 0 at ux = %.4g m); "
                    "no friction without contact (press deeper: --uz)\n", st.ux);
        return;
      }
    return;
  }
  if (peak_reached(steps))
    std::printf("  static friction (peak mu of the shear steps): mu = %.4g at ux = %.4g m (step %d)\n", peak->mu,
                peak->ux, int(peak - steps.data()) + 1);
  else
    std::printf("  static friction: mu >= %.4g (highest at ux = %.4g m, step %d; not turned over: the peak lies beyond "
                "--ux)\n",
                peak->mu, peak->ux, int(peak - steps.data()) + 1);
}

void print_step_header() {
  std::printf("  %4s %10s %10s %11s %11s %8s %8s %9s %10s %10s %5s %6s %8s\n", "step", "uz [m]", "ux [m]", "Fz [N]",
              "Fx [N]", "mu", "A/A0", "sigma*", "sep [m]", "pen [m]", "sig", "lin", "wall [s]");
  std::fflush(stdout);
}

void print_step_row(int k, const ContactStep& st) {
  // Without contact there is no friction coefficient to show (Fx/Fz of nothing).
  const std::string mu = st.area_fraction > 0 && st.fz > 0 ? number_text(st.mu) : "--";
  std::printf("  %4d %10.4g %10.4g %11.4e %11.4e %8s %8.4f %9.4g %10.3e %10.2e %5d %6d %8.2f%s\n", k, st.uz, st.ux,
              st.fz, st.fx, mu.c_str(), st.area_fraction, st.sigma_star, st.separation, st.max_penetration,
              st.signorini_iterations, st.linear_iterations, st.wall_s,
              !st.converged ? "  FAILED" : st.failed_attempts > 0 ? "  (cut back)" : "");
  std::fflush(stdout);
}

}  // namespace wr::app
