#include "lib/fem/slow_mode_extrapolation.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace wr {
namespace {

void check(PetscErrorCode ierr, const char* what) {
  if (ierr) throw std::runtime_error(std::string("PETSc error in ") + what);
}

}  // namespace

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

double SlowModeExtrapolation::after_iteration(Vec u) {
  if (!every_ || ++count_ % every_ != 0) return 0.0;
  check(VecWAXPY(change_, -1.0, start_, u), "VecWAXPY");  // this block's change
  double factor = 0.0;
  if (have_previous_) {
    PetscReal now = 0, before = 0;
    PetscScalar dot = 0;
    check(VecNorm(change_, NORM_2, &now), "VecNorm");
    check(VecNorm(previous_, NORM_2, &before), "VecNorm");
    check(VecDot(change_, previous_, &dot), "VecDot");
    const double q = before > 0 ? now / before : 1.0;
    const double cosine = now > 0 && before > 0 ? dot / (now * before) : 0.0;
    if (cosine > kMinCosine && q < kMaxRatio) {
      factor = std::min(q / (1 - q), kMaxFactor);
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

}  // namespace wr
