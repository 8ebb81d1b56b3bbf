#include "lib/contact/friction_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace wr {

double friction_drift(const std::vector<double>& mu, const std::vector<double>& damping, double nominal_damping,
                      int window) {
  const int n = int(std::min(mu.size(), damping.size()));
  const int h = std::min(window / 2, (n - 1) / 2);
  if (h < 1 || !(nominal_damping > 0)) return std::numeric_limits<double>::quiet_NaN();
  // The change of mu from iteration `from` to `to`, scaled to the nominal damping: the steps
  // between them were taken with damping[from .. to - 1].
  const auto change = [&](int from, int to) {
    double alpha = 0;
    for (int k = from; k < to; ++k) alpha += damping[std::size_t(k)];
    alpha /= double(to - from);
    return std::abs(mu[std::size_t(to)] - mu[std::size_t(from)]) * nominal_damping / std::max(alpha, 1e-12);
  };
  const int last = n - 1;
  const double d2 = change(last - h, last), d1 = change(last - 2 * h, last - h);
  if (d2 == 0) return 0.0;
  const double r = d1 > 0 ? std::min(d2 / d1, 0.95) : 0.95;
  return d2 * r / (1 - r) / std::max(std::abs(mu[std::size_t(last)]), kFrictionMuFloor);
}

ValidityCheck friction_convergence_check(const std::vector<ContactStep>& steps) {
  ValidityCheck c{"friction converged", true, "", false};
  int assessed = 0, worst = -1;
  double worst_drift = 0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const ContactStep& s = steps[k];
    if (!in_shear_contact(s) || !std::isfinite(s.mu_drift)) continue;  // no contact: no mu to converge
    ++assessed;
    if (worst < 0 || s.mu_drift > worst_drift) {
      worst = int(k);
      worst_drift = s.mu_drift;
    }
  }
  char buf[320];
  if (assessed == 0) {
    c.detail = "no shear step with a measured drift of mu";
    return c;
  }
  c.passed = worst_drift <= kFrictionDriftLimit;
  std::snprintf(buf, sizeof buf,
                "mu of step %d (%.4g) may still change by about %.2g %% (estimated from its last %d Signorini "
                "iterations; limit %.2g %%)%s",
                worst + 1, steps[std::size_t(worst)].mu, 100 * worst_drift, kFrictionWindow, 100 * kFrictionDriftLimit,
                c.passed ? "" : ": the face is still sliding, mu is where the iteration stopped (tighten --tol)");
  c.detail = buf;
  return c;
}

ValidityCheck friction_peak_check(const std::vector<ContactStep>& steps) {
  ValidityCheck c{"friction peak reached", true, "", false};
  const ContactStep* peak = peak_friction(steps);
  if (!peak) {
    c.detail = "no converged shear step in contact";
    return c;
  }
  c.passed = peak_reached(steps);
  char buf[320];
  std::snprintf(buf, sizeof buf,
                c.passed ? "mu peaks at %.4g (ux %.4g m, step %d) and falls after it"
                         : "mu has not turned over (its highest, %.4g at ux %.4g m, step %d, is neither followed by a "
                           "step %.0f %% lower nor by two lower ones): the static friction is at least this; shear "
                           "further (--ux; a run with --checkpoint continues with --restart)",
                peak->mu, peak->ux, int(peak - steps.data()) + 1, 100 * kPeakFall);
  c.detail = buf;
  return c;
}

}  // namespace wr
