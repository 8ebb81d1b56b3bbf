#pragma once
// Stagnation of an iteration's error or change history (shared by the spectral solvers and
// the FEM's adaptive damping).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace wr {

// True when the best value of the last `window` entries of `history` is not below half the best
// of the `window` before: a residual that no longer decreases. False while the history is
// shorter than 2 x window, and for window 0.
inline bool stagnated(const std::vector<double>& history, std::size_t window) {
  if (window == 0 || history.size() < 2 * window) return false;
  const auto end = history.end();
  const double recent = *std::min_element(end - long(window), end);
  const double before = *std::min_element(end - 2 * long(window), end - long(window));
  return recent > 0.5 * before;
}

}  // namespace wr
