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

const ContactStep* peak_friction(const std::vector<ContactStep>& steps) {
  const ContactStep* best = nullptr;
  for (const ContactStep& st : steps)
    if (st.converged && st.ux != 0 && (!best || st.mu > best->mu)) best = &st;
  return best;
}

bool peak_reached(const std::vector<ContactStep>& steps) {
  const ContactStep* peak = peak_friction(steps);
  if (!peak) return false;
  for (const ContactStep* st = peak + 1; st < steps.data() + steps.size(); ++st)
    if (st->converged && st->ux != 0 && st->mu < peak->mu) return true;
  return false;
}

}  // namespace wr
