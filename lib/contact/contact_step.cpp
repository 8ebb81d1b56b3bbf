#include "lib/contact/contact_step.hpp"

namespace wr {

const ContactStep* peak_friction(const std::vector<ContactStep>& steps) {
  const ContactStep* best = nullptr;
  for (const ContactStep& st : steps)
    if (st.converged && st.ux != 0 && (!best || st.mu > best->mu)) best = &st;
  return best;
}

}  // namespace wr
