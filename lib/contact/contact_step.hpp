#pragma once
// One load step of a contact experiment (Problem A or B, thesis sec. 4.2.2), whichever model
// computed it (FEM: lib/fem/block_press_shear.hpp; spectral: lib/spectral/spectral_press_shear.hpp).
// SI units: m, N, m^2; forces for the stated E.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

struct ContactStep {
  double uz = 0, ux = 0, fz = 0, fx = 0, fy = 0;
  double area_fraction = 0, contact_area = 0, sigma_star = 0, mu = 0;
  double separation = 0, max_penetration = 0;
  // FEM: where the deepest face node is (deformed x, y, m) and how many nodes are deeper than
  // the allowed penetration: one stray node on a steep flank or a whole patch.
  double penetration_x = 0, penetration_y = 0;
  std::size_t nodes_over_penetration = 0;
  // FEM: geometry (Signorini), active-set and CG iterations; spectral: 1, 0 and the
  // constrained-CG iterations.
  int signorini_iterations = 0, active_set_iterations = 0, linear_iterations = 0;
  int extrapolations = 0;  // FEM: slow-mode (Aitken) jumps taken in the step
  int rejected_jumps = 0;  // FEM: of them, undone (the contact set collapsed after the jump)
  // FEM with cutbacks: failed attempts at longer increments just before this step (their wall
  // time is included in wall_s).
  int failed_attempts = 0;
  // FEM with the secant predictor: the ratio r of the extrapolation the step started from
  // (ContactTestOptions::secant_predictor); 0: it started from the last converged state.
  double predictor_ratio = 0;
  // FEM with a coarse start (ContactTestOptions::coarse_refine): the coarse block's Signorini
  // iterations and wall time in this step (included in wall_s), and whether it converged.
  int coarse_iterations = 0;
  double coarse_wall_s = 0;
  bool coarse_converged = false;
  double wall_s = 0;
  double wall_linearise = 0, wall_rotate = 0, wall_solve = 0;  // s, phases of the step
  bool converged = false;
  std::string message;
  std::vector<double> history;  // the solver's convergence measure per iteration
  // FEM: mu of each Signorini iteration's linearised solution, and how much it still changed
  // at the end (lib/contact/friction_convergence.hpp; NaN where not measured).
  std::vector<double> mu_history;
  double mu_drift = std::numeric_limits<double>::quiet_NaN();
  // Contact-face maps when requested, row-major (rows = y): FEM (ny+1) x (nx+1) face nodes,
  // spectral ny x nx grid points. Pressure Pa, gap m, status 1 in contact / 0 free.
  std::vector<double> face_pressure, face_gap, face_status;
};

// Hears of each load step of a run as it ends (progress lines, live tables); may be empty.
using StepListener = std::function<void(const ContactStep&)>;

// A step whose forces, area or friction came out non-finite (NaN, Inf: a load beyond double
// precision's range, or a solver breakdown) is no result: it is marked not converged with the
// reason in `message`, so that it ends the run as a failure (exit 3) instead of a number.
// Returns whether the step was finite.
bool fail_if_not_finite(ContactStep& step);

// A converged shear step (ux != 0) that still touches the obstacle (A/A0 > 0, Fz > 0): only such
// a step has a friction coefficient; once the block has lifted off, Fx/Fz is noise over nothing.
bool in_shear_contact(const ContactStep& st);

// The static friction of a shear test: the shear step in contact with the largest mu; nullptr
// when there is none (no shear phase, or contact lost in all of it).
const ContactStep* peak_friction(const std::vector<ContactStep>& steps);

// A fall of mu below the peak by more than this fraction, in one converged shear step, is a
// turn-over; a smaller one only when a second converged step after the peak lies below it too.
// Why: the Signorini tolerance leaves each step's mu a little off the curve, and at --tol 1e-3
// the thesis scene's rising curve dipped by 0.75 % (8 -> 9 mm, then rose 6 %) and 0.8 % (4 ->
// 4.5 mm) at refine 1: a plain "a later mu is lower" stopped --to-peak at such a dip.
constexpr double kPeakFall = 0.03;

// Whether the shear curve turned over after its peak (kPeakFall). When it has not (the peak is the last converged shear step), the static friction is only
// bounded from below by the peak mu: on rough surfaces (rms slope ~2) mu still rises after the
// top has moved half the block's side, so a short --ux reports the loading curve, not the peak.
bool peak_reached(const std::vector<ContactStep>& steps);

// One step as every contact record holds it (`contact --json`, the sweeps' run records; SI
// units; null where not measured).
nlohmann::json contact_step_json(const ContactStep& s);

}  // namespace wr
