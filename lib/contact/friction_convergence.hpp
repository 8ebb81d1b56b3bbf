#pragma once
// Is a shear step's friction converged? The geometry (Signorini) iteration of the FEM can meet
// its tolerance on the face displacement while the friction ratio still creeps: the block's
// face slides along the obstacle a little further every iteration (the slow mode of
// Algorithm 1 with linearised constraints), which barely changes Fz or the contact set but
// steadily lowers Fx. Measured on a 50 x 50 dataset-A-like scene (h0 0.1 mm, refine 2,
// uz 1.5 mm, ux 1 mm): mu fell from 0.19 after the first iteration to 0.049 after 114 and was
// still falling. A mu read off such an iteration is where it stopped, not a result.
//
// The measure: an estimate of how far mu still is from the iteration's limit, from its last
// two half-windows of h Signorini iterations (mu_k: the friction ratio of the k-th linearised
// solution). Their changes d1 (older) and d2 (newer) are scaled to the nominal damping, since
// the iterate moves by alpha x the correction and a damping lowered by the stagnation guard
// slows the creep without ending it. If mu approaches its limit geometrically, the remaining
// change is d2 r / (1 - r) with r = d2 / d1 (exact for a geometric sequence); r is capped at
// 0.95, so a steady creep (r ~ 1) reads as at least 19 more half-windows of it:
//   drift = d2 r / (1 - r) / max(|mu_n|, kFrictionMuFloor).
#include <vector>

#include "lib/contact/contact_step.hpp"
#include "lib/contact/model_ladder.hpp"

namespace wr {

// Largest estimated remaining relative change of a shear step's mu that counts as converged.
constexpr double kFrictionDriftLimit = 0.05;
// Signorini iterations the estimate looks back over (two half-windows).
constexpr int kFrictionWindow = 10;
// Below this |mu| the drift is measured in absolute terms (relative to this value): the mu of
// a flat or symmetric scene is noise around 0.
constexpr double kFrictionMuFloor = 1e-3;

// The drift defined above; NaN when there are fewer than three iterations. `mu` and `damping`
// hold one entry per Signorini iteration (same length; damping[k] is the alpha_c applied after
// iteration k); `nominal_damping` > 0. With fewer than window + 1 iterations the half-windows
// shrink to (n - 1) / 2.
double friction_drift(const std::vector<double>& mu, const std::vector<double>& damping, double nominal_damping,
                      int window = kFrictionWindow);

// The "friction converged" check of a finished run: every converged shear step (ux != 0) whose
// drift was measured has drift <= kFrictionDriftLimit. An accuracy flag (decides_model false):
// no cheaper model does better. Passes, saying so, when no step was assessed.
ValidityCheck friction_convergence_check(const std::vector<ContactStep>& steps);

// The "friction peak reached" check: the shear curve turned over (peak_reached), so the peak mu
// is the scene's static friction and not a point on its loading branch. An accuracy flag
// (decides_model false): the cure is a longer --ux, not another model. Passes, saying so, when
// the run has no converged shear step.
ValidityCheck friction_peak_check(const std::vector<ContactStep>& steps);

}  // namespace wr
