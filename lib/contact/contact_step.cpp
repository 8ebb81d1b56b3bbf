#include "lib/contact/contact_step.hpp"

namespace wr {

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
