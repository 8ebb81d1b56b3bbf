#include "lib/contact/adaptive_damping.hpp"

#include <algorithm>

#include "lib/core/stagnation.hpp"

namespace wr {

void AdaptiveDamping::after_correction(double cosine) {
  if (cosine < kReverse)
    alpha_ = std::max(0.5 * alpha_, kMinAlpha);
  else if (cosine > kKeep)
    alpha_ = std::min(1.5 * alpha_, cap_);
}

void AdaptiveDamping::after_change(const std::vector<double>& history) {
  const std::size_t k = history.size();
  if (k - last_cut_ < 2 * kWindow || !stagnated(history, kWindow) || cap_ <= kMinCap) return;
  cap_ = std::max(0.5 * cap_, kMinCap);
  alpha_ = std::min(alpha_, cap_);
  last_cut_ = k;
}

}  // namespace wr
