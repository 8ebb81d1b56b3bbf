#include "lib/contact/contact_step.hpp"

#include <cmath>

namespace wr {

bool fail_if_not_finite(ContactStep& st) {
  const bool finite = std::isfinite(st.fz) && std::isfinite(st.fx) && std::isfinite(st.fy) &&
                      std::isfinite(st.area_fraction) && std::isfinite(st.sigma_star) &&
                      (st.fz == 0 || std::isfinite(st.mu));
  if (!finite) {
    st.converged = false;
    st.message = "non-finite result (Fz " + std::to_string(st.fz) + " N, Fx " + std::to_string(st.fx) +
                 " N, A/A0 " + std::to_string(st.area_fraction) +
                 "): the load or the surface is beyond double precision's range, or the solver broke down";
  }
  return finite;
}

bool in_shear_contact(const ContactStep& st) {
  return st.converged && st.ux != 0 && st.area_fraction > 0 && st.fz > 0 && std::isfinite(st.mu);
}

const ContactStep* peak_friction(const std::vector<ContactStep>& steps) {
  const ContactStep* best = nullptr;
  for (const ContactStep& st : steps)
    if (in_shear_contact(st) && (!best || st.mu > best->mu)) best = &st;
  return best;
}

bool peak_reached(const std::vector<ContactStep>& steps) {
  const ContactStep* peak = peak_friction(steps);
  if (!peak) return false;
  int below = 0;
  for (const ContactStep* st = peak + 1; st < steps.data() + steps.size(); ++st) {
    if (!in_shear_contact(*st) || !(st->mu < peak->mu)) continue;
    if (st->mu < peak->mu - kPeakFall * std::abs(peak->mu) || ++below == 2) return true;
  }
  return false;
}

nlohmann::json contact_step_json(const ContactStep& s) {
  return {{"uz", s.uz},
          {"ux", s.ux},
          {"fz", s.fz},
          {"fx", s.fx},
          {"fy", s.fy},
          {"area_fraction", s.area_fraction},
          {"contact_area", s.contact_area},
          {"sigma_star", s.sigma_star},
          {"mu", s.mu},
          {"separation", s.separation},
          {"max_penetration", s.max_penetration},
          {"max_penetration_at", {s.penetration_x, s.penetration_y}},
          {"nodes_over_max_penetration", s.nodes_over_penetration},
          {"signorini_iterations", s.signorini_iterations},
          {"active_set_iterations", s.active_set_iterations},
          {"linear_iterations", s.linear_iterations},
          {"extrapolations", s.extrapolations},
          {"rejected_jumps", s.rejected_jumps},
          {"failed_attempts", s.failed_attempts},
          {"predictor_ratio", s.predictor_ratio},
          {"wall_s", s.wall_s},
          {"converged", s.converged},
          {"message", s.message},
          {"residual_history", s.history},
          // How much mu still moved at the end (friction_convergence.hpp); null where not measured.
          {"mu_drift", std::isfinite(s.mu_drift) ? nlohmann::json(s.mu_drift) : nlohmann::json(nullptr)},
          {"mu_history", s.mu_history},
          {"coarse_start", s.coarse_iterations > 0
                               ? nlohmann::json{{"signorini_iterations", s.coarse_iterations},
                                                {"wall_s", s.coarse_wall_s},
                                                {"converged", s.coarse_converged}}
                               : nlohmann::json(nullptr)}};
}

}  // namespace wr
