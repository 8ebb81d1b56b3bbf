#pragma once
// How long Algorithm 1 (thesis sec. 4.2) goes on after its change test has passed while a face
// node is still deeper in the obstacle than allowed (--max-penetration).
//
// Why: on rough obstacles the iteration chatters and the damping cap averages the chatter out
// (AdaptiveDamping), so the capped change can pass the tolerance while the averaged iterate
// is still settling out of the obstacle. A fixed number of retries judged that by count, not by
// progress: on the 300 x 300 dataset-A scene (h0 0.305 mm, refine 2, step 2 of uz 9 mm) the
// deepest node fell 1.19e-4 -> 8.8e-5 -> 6.5e-5 -> 5.2e-5 -> 4.1e-5 -> 3.3e-5 m over the last
// iterations, and the step failed at 3.31e-5 m against a limit of 3.05e-5 m because its three
// retries were spent. Now the iteration goes on while the deepest node keeps getting
// shallower and gives up after kPatience retries in a row without a new shallowest depth (the
// max_outer_iterations cap still holds).
#include <cmath>

namespace wr {

class PenetrationRetries {
 public:
  static constexpr int kPatience = 3;        // retries in a row that may bring no progress
  static constexpr double kProgress = 0.95;  // progress: below this times the shallowest so far

  // The change test passed with the deepest node `depth` (m) over the limit: whether to go on.
  bool retry(double depth) {
    ++count_;
    if (depth < kProgress * shallowest_) {
      shallowest_ = depth;
      stalled_ = 0;
    } else {
      ++stalled_;
    }
    return stalled_ < kPatience;
  }
  int count() const { return count_; }

 private:
  double shallowest_ = INFINITY;
  int stalled_ = 0, count_ = 0;
};

}  // namespace wr
