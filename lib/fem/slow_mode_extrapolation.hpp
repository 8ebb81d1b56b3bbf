#pragma once
// Vector Aitken extrapolation of the Signorini (geometry) iteration along its slow mode.
//
// Why: with linearised constraints, Algorithm 1 (thesis sec. 4.2) converges linearly, and on
// rough obstacles one mode is slow: the contact face creeping along the obstacle, a little
// further every iteration (contraction 0.9-0.99 per iteration), while the fast modes die out in
// a few. Over a block of `every` iterations the iterate then moves along an almost fixed
// direction d by a factor q < 1 less each block; the rest of the geometric series,
// d (q + q^2 + ...) = d q / (1 - q), is added in one jump (the Aitken delta-squared step on the
// block changes). The next iteration re-linearises at the extrapolated configuration, so a jump
// that overshoots costs iterations, never correctness: convergence is still judged by the
// iteration's own criterion.
//
// Measured (50 x 50 obstacle, h0 0.1 mm, refine 2, uz 1.5 mm, tol 1e-4, 2 ranks): 103 Signorini
// iterations and 1744 CG iterations, against 214 and 3593 without.
//
// A jump is taken only when two consecutive block changes point the same way (cosine > 0.9)
// and shrink (q < 0.99); its factor is capped at kMaxFactor. After a jump the next two blocks
// are measured afresh.
#include <petscvec.h>

#include <array>

namespace wr {

// The jump factor q / (1 - q) (at most kMaxFactor) for a block change of norm `now` after one
// of norm `before`, `dot` their inner product; 0 unless they point the same way (cosine >
// kMinCosine) and shrink (q < kMaxRatio). Shared by both extrapolations below.
double aitken_jump_factor(double now, double before, double dot);

// Whether a jump overshot: the relative change of the first iteration after it,
// `change_after`, is more than kMaxJumpGrowth times the change of the iteration that jumped,
// `change_before`; the caller then undoes it. Why: had the creep been the geometric series the
// jump sums, the next correction would be the fast modes' rest, not much larger than before; a
// much larger one says the jump went mostly where the creep was not heading (the creep slowed
// or stopped, e.g. at a wall, before the series' limit). Measured on FEM contact steps (change
// after / before): jumps that paid off 1.9 and 2.8 (100 x 100 scene, uz 1.5 mm) and 4.6
// (300 x 300 dataset-A scene, step 1 of uz 9 mm; undoing it and the later ratios 4.4 and 5.0
// cost that step 8 iterations more); jumps that overshot 14 and 12 (50 x 50, --tol 1e-4: they
// took the deepest node from 8e-7 m to 1.5e-5 m and from 5.6e-6 m to 1.3e-4 m, and the step
// failed with a node too deep) and 7.5 (300 x 300, step 2: eight iterations of recovery).
constexpr double kMaxJumpGrowth = 6.0;
inline bool jump_overshot(double change_after, double change_before) {
  return change_before > 0 && change_after > kMaxJumpGrowth * change_before;
}

class SlowModeExtrapolation {
 public:
  static constexpr double kMinCosine = 0.9;
  static constexpr double kMaxRatio = 0.99;
  static constexpr double kMaxFactor = 20.0;

  // `like`: a vector of the iterate's layout; `every` >= 2 iterations per block (0 or 1: off).
  SlowModeExtrapolation(Vec like, int every);
  ~SlowModeExtrapolation();
  SlowModeExtrapolation(const SlowModeExtrapolation&) = delete;
  SlowModeExtrapolation& operator=(const SlowModeExtrapolation&) = delete;

  // Call once after every iteration with its new iterate `u` (collective). At the end of a
  // block it may move `u` in place; returns the factor of that jump, 0 when none. Before a
  // jump, `u` is copied into `before_jump` (if given, same layout) so that the caller can undo it.
  double after_iteration(Vec u, Vec before_jump = nullptr);
  // Another jump moved `u`: measure two fresh blocks from it (collective).
  void restart(Vec u);
  int jumps() const { return jumps_; }

 private:
  int every_ = 0, count_ = 0, jumps_ = 0;
  bool have_previous_ = false;
  Vec start_ = nullptr, previous_ = nullptr, change_ = nullptr;
};

// The same Aitken step on a few observables: the contact face's rigid in-plane modes.
//
// Why: the slow mode of a block with a fixed top lies mostly in two in-plane motions of the
// face over the obstacle, which the tangent planes of the linearisation lock (only the
// re-linearisation lets them advance): its slide (50 x 50 scene, uz 1.5 mm: the mean x
// correction is 60-80 % of the rms x correction late in the step) and its uniform lateral
// expansion, the Poisson bulge of the pressed block (300 x 300 dataset-A scene, uz 4.5 mm: 96 %
// of the tangential correction from iteration 5 on). The fast modes' chatter around them keeps
// the whole-vector test (cosine > 0.9) from firing; the face's modal coordinates average it out.
// The jump is returned in modal coordinates; the caller spreads it through the block (fading
// linearly to the fixed top), and the next linearisation relaxes the rest.
class FaceModeExtrapolation {
 public:
  static constexpr int kModes = 4;  // slide x, slide y, dilatation, twist (FaceModeBasis in elastic_block.cpp)
  using Modes = std::array<double, kModes>;
  explicit FaceModeExtrapolation(int every) : every_(every >= 2 ? every : 0) {}
  // Call after every iteration with the face's modal coordinates; returns the modal jump to
  // add, all 0 when none is taken.
  Modes after_iteration(const Modes& modes);
  // Another jump moved the iterate: measure two fresh blocks from `modes`.
  void restart(const Modes& modes);
  int jumps() const { return jumps_; }

 private:
  int every_ = 0, count_ = 0, jumps_ = 0;
  bool have_previous_ = false, started_ = false;
  Modes start_{}, previous_{};
};

}  // namespace wr
