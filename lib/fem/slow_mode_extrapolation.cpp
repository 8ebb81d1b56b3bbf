#include "lib/fem/slow_mode_extrapolation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/fem/petsc_session.hpp"

namespace wr {
namespace {

using petsc::check;

}  // namespace

double aitken_jump_factor(double now, double before, double dot) {
  if (!(now > 0 && before > 0)) return 0.0;
  const double q = now / before, cosine = dot / (now * before);
  if (cosine <= SlowModeExtrapolation::kMinCosine || q >= SlowModeExtrapolation::kMaxRatio) return 0.0;
  return std::min(q / (1 - q), SlowModeExtrapolation::kMaxFactor);
}

SlowModeExtrapolation::SlowModeExtrapolation(Vec like, int every) : every_(every >= 2 ? every : 0) {
  if (!every_) return;
  check(VecDuplicate(like, &start_), "VecDuplicate");
  check(VecDuplicate(like, &previous_), "VecDuplicate");
  check(VecDuplicate(like, &change_), "VecDuplicate");
  check(VecCopy(like, start_), "VecCopy");
}

SlowModeExtrapolation::~SlowModeExtrapolation() {
  if (start_) VecDestroy(&start_);
  if (previous_) VecDestroy(&previous_);
  if (change_) VecDestroy(&change_);
}

double SlowModeExtrapolation::after_iteration(Vec u, Vec before_jump) {
  if (!every_ || ++count_ % every_ != 0) return 0.0;
  check(VecWAXPY(change_, -1.0, start_, u), "VecWAXPY");  // this block's change
  double factor = 0.0;
  if (have_previous_) {
    PetscReal now = 0, before = 0;
    PetscScalar dot = 0;
    check(VecNorm(change_, NORM_2, &now), "VecNorm");
    check(VecNorm(previous_, NORM_2, &before), "VecNorm");
    check(VecDot(change_, previous_, &dot), "VecDot");
    factor = aitken_jump_factor(now, before, dot);
    if (factor > 0) {
      if (before_jump) check(VecCopy(u, before_jump), "VecCopy");
      check(VecAXPY(u, factor, change_), "VecAXPY");
      ++jumps_;
    }
  }
  // After a jump the block changes are measured afresh: the jump is not part of the series.
  have_previous_ = factor == 0.0;
  check(VecCopy(change_, previous_), "VecCopy");
  check(VecCopy(u, start_), "VecCopy");
  return factor;
}

void SlowModeExtrapolation::restart(Vec u) {
  if (!every_) return;
  check(VecCopy(u, start_), "VecCopy");
  have_previous_ = false;
  count_ = 0;
}

FaceModeExtrapolation::Modes FaceModeExtrapolation::after_iteration(const Modes& modes) {
  Modes jump{};
  if (!every_) return jump;
  if (!started_) {
    restart(modes);
    return jump;
  }
  if (++count_ % every_ != 0) return jump;
  Modes change;
  double now = 0, before = 0, dot = 0;
  for (int k = 0; k < kModes; ++k) {
    change[k] = modes[k] - start_[k];
    now += change[k] * change[k];
    before += previous_[k] * previous_[k];
    dot += change[k] * previous_[k];
  }
  const double factor = have_previous_ ? aitken_jump_factor(std::sqrt(now), std::sqrt(before), dot) : 0.0;
  const bool jumped = factor > 0;
  if (jumped) {
    for (int k = 0; k < kModes; ++k) jump[k] = factor * change[k];
    ++jumps_;
  }
  have_previous_ = !jumped;
  previous_ = change;
  for (int k = 0; k < kModes; ++k) start_[k] = modes[k] + jump[k];
  return jump;
}

void FaceModeExtrapolation::restart(const Modes& modes) {
  start_ = modes;
  started_ = true;
  count_ = 0;
  have_previous_ = false;
}

}  // namespace wr
