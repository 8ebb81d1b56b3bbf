#pragma once
// The damping alpha_c of the Signorini (geometry) iteration, thesis sec. 4.2, Algorithm 1: the
// correction c = u* - u is scaled by alpha_c before it is added (the thesis fixes 0.8). Used by
// the FEM's Signorini iteration and by the spectral shear test's geometry iteration.
//
// Why adaptive: nodes on kinks of a rough obstacle can chatter between two contact states (the
// linearised map is discontinuous there), and a fixed alpha_c then never converges.
// - A correction that reverses the previous one (cosine < kReverse) halves alpha (down to
//   kMinAlpha); corrections that keep their direction (cosine > kKeep) grow it 1.5x per
//   iteration, up to the ceiling.
// - When the change stalls all the same (stagnated(): the best change of the last kWindow
//   iterations is not half the best of the kWindow before), the ceiling halves (down to
//   kMinCap), at most once per 2 kWindow iterations. The iterates then average the chatter out
//   (a Krasnoselskii-Mann step). The FEM judges convergence on the capped step, step_change():
//   the change the iterate still makes, kept honest by its penetration check; the spectral
//   shear judges the residual itself and gives up only once exhausted().
#include <cstddef>
#include <vector>

namespace wr {

class AdaptiveDamping {
 public:
  static constexpr double kReverse = -0.3, kKeep = 0.7;  // cosines of consecutive corrections
  static constexpr double kMinAlpha = 0.01, kMinCap = 0.05;
  static constexpr std::size_t kWindow = 15;  // iterations

  // `nominal` in (0, 1]: the starting damping and ceiling.
  explicit AdaptiveDamping(double nominal) : nominal_(nominal), alpha_(nominal), cap_(nominal) {}

  // After a correction whose cosine with the previous correction is `cosine` (NaN: no change).
  void after_correction(double cosine);
  // After the relative change of an iteration was appended to `history` (all of the step's).
  void after_change(const std::vector<double>& history);

  double alpha() const { return alpha_; }  // to apply to this iteration's correction
  bool capped() const { return cap_ < nominal_; }
  bool exhausted() const { return cap_ <= kMinCap; }  // the ceiling cannot be cut further
  // The change the convergence test judges: times the ceiling once the ceiling was cut.
  double step_change(double change) const { return capped() ? cap_ * change : change; }

 private:
  double nominal_, alpha_, cap_;
  std::size_t last_cut_ = 0;  // history length at the last cut of the ceiling
};

}  // namespace wr
