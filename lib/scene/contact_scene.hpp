#pragma once
// One contact experiment (thesis sec. 4.2.2: Problem A, then B) on one obstacle with a model of
// the ladder, as a sweep runs it: the scene's parameters in one place, the model's own options
// derived from them, and one record per run whichever model computed it.
//
// The FEM runs on `comm` (every rank of it shares the block); the spectral model on threads in
// the calling process. The analytic model has no shear test and is refused.
#include <mpi.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/contact/contact_step.hpp"
#include "lib/contact/model_ladder.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/height_map.hpp"
#include "lib/fem/amg_hierarchy.hpp"
#include "lib/fem/linear_solver.hpp"
#include "lib/fem/block_press_shear.hpp"
#include "lib/spectral/spectral_press_shear.hpp"

namespace wr {

struct ContactScene {
  ContactModel model = ContactModel::fem;
  bool shear = true;          // Problem B after A
  double uz = 0;              // m, final normal displacement of the top (> 0)
  double ux = 0;              // m, final tangential displacement (shear, > 0)
  int normal_steps = 3, shear_steps = 3;
  bool to_peak = false;       // FEM: shear until mu(ux) turns over (ContactTestOptions::to_peak)
  int refine = 1;             // contact-face spacing = obstacle spacing / refine
  double young = 1.0, poisson = 0.45;  // Pa, -
  double height = 0;          // m, block height (0: the period, a cube)
  double thickness = 0;       // m, spectral layer (0: the block height; +inf: the half-space)
  double pressure = 0;        // Pa, spectral load control instead of uz (normal contact only)
  double damping = 0.8;       // of the geometry (Signorini) iteration
  int extrapolate_every = 5;  // FEM: slow-mode jumps every this many Signorini iterations (0: off)
  double tolerance = 1e-4;    // relative change per geometry (Signorini) iteration
  double spectral_tolerance = 1e-8;  // Polonsky-Keer error
  int max_iterations = 0;     // per step (0: the model's default)
  int cutbacks = 0;           // FEM: halvings of a failed load step (ContactTestOptions::max_cutbacks)
  SecantPredictor predictor = SecantPredictor::press;  // FEM: ContactTestOptions::secant_predictor
  // FEM: deepest penetration a converged step may leave, m; 0: 0.1 x the obstacle's rms height.
  // A wet obstacle's rms height is lower than its ground's (pools fill the valleys) while its
  // asperities, where the contact is, are the same: sweeps judge every coverage by the ground's.
  double max_penetration = 0;
  int threads = 1;            // spectral FFT threads
  FftPlanning planning = FftPlanning::estimate;  // spectral FFT plans (lib/core/fft.hpp)
  // FEM: constrain each contact node along the normal of the obstacle facet its ray hits (the
  // direction of a frictionless contact force on the rigid surface) instead of the smooth blend
  // of the face's vertex normals; tangential forces then come from the obstacle's flanks.
  bool facet_normals = false;
  double facet_band = 0;  // > 0: facet normals blended into the smooth ones near facet edges
  // FEM mesh and solver (ContactTestOptions says what each does).
  int layers_per_level = 2;   // brick layers at each in-plane spacing
  int max_coarsenings = 16;   // in-plane doublings of the spacing away from the face
  int coarse_refine = 0;      // nested iteration's coarse block (0: off; experimental)
  bool face_modes = false;    // slow-mode jumps along the face's rigid modes too (experimental)
  double ksp_rtol = 1e-7;     // CG tolerance of a step's final linear solves
  bool follow_geometry = true;  // false: one linearisation with vertical normals
  ContactIteration iteration = ContactIteration::signorini;  // FEM: Algorithm 1 or Newton (C2 obstacle)
  double curvature = 1.0;       // FEM Newton: scale of the constraints' second-order term
  double block_normals = 0;   // > 0: the block's own normals, relaxed so (experimental)
  AmgHierarchy amg = AmgHierarchy::automatic;
  LinearSolver solver = LinearSolver::automatic;  // FEM: sparse Cholesky or AMG-preconditioned CG
};

// The grid a model runs on, known once it is set up (for a caller that prints it first).
struct SceneSetup {
  std::size_t nx = 0, ny = 0;  // obstacle (fem) or spectral lattice points
  double dx = 0;               // m
  double rms_slope = 0;        // of the obstacle as the model sees it
  double thickness = 0;        // m, spectral layer; +inf: half-space; 0: fem
};

// What a run of a scene needs beyond the scene itself: where its results go while it runs.
struct SceneRunHooks {
  std::function<void(const SceneSetup&)> on_setup;  // before the first step (may be empty)
  StepListener on_step;  // after every step (may be empty)
  const HeightMap* ground = nullptr;  // fem: the dry surface under a wet obstacle (penetration limit)
  bool face_maps = false;         // keep the contact-face maps of every step
  std::string vtu_path;           // fem: write the deformed block of the last step
  double progress_every_s = 0;    // fem: a progress line at most this often within a step
  bool trace = false;             // fem: every Signorini iteration on stderr
  std::string checkpoint_path;    // fem: write a checkpoint after every converged step (contact_checkpoint.hpp)
  std::string restart_path;       // fem: continue from this checkpoint
};

struct SceneResult {
  std::string model;          // "fem" or "spectral"
  std::vector<ContactStep> steps;
  bool failed = false;
  std::string message;        // why it failed
  std::size_t unknowns = 0;   // FEM nodes or spectral grid points
  double wall_s = 0;
  nlohmann::json validity;    // the model's checks for this scene
  // Convenience: the static friction (peak mu of the converged shear steps, NaN without one)
  // and the contact-area fraction at the peak and at the end of the normal load.
  double mu_peak = 0, ux_peak = 0, area_at_peak = 0, area_normal = 0, fz_normal = 0;
  // The model's own record (mesh, timings, grid) for a caller that reports it in full.
  std::optional<ContactTestResult> fem;
  std::optional<SpectralTestResult> spectral;
  // The model's options the scene was run with.
  std::optional<ContactTestOptions> fem_options;
  std::optional<SpectralTestOptions> spectral_options;
};

// Every scene option at once, before any work: the one validator that `contact` and the sweeps
// share. Throws InputError naming the option at fault (non-finite or out-of-range values, a
// shear test asked of the analytic model, step records that cannot fit in memory).
void check_contact_scene(const ContactScene& s);

// `obstacle` periodic, no NaN. A step that does not converge ends the run: failed, with the
// finished steps kept.
SceneResult run_contact_scene(const HeightMap& obstacle, const ContactScene& s, MPI_Comm comm,
                              const SceneRunHooks& hooks = {});
// The same, for runs among many (sweeps): an exception becomes a failed result with its message.
SceneResult run_contact_scene_caught(const HeightMap& obstacle, const ContactScene& s, MPI_Comm comm,
                                     const SceneRunHooks& hooks = {});

// The analytic model's normal curve: Persson's contact area (erf form, eq. 3.162 / 5.3) at each
// of the scene's normal_steps mean pressures up to s.pressure (> 0, Pa), for an obstacle of rms
// slope `rms_slope` and projected area `area` (m^2). No separation (not part of the theory: NaN).
std::vector<ContactStep> analytic_normal_curve(const ContactScene& s, double rms_slope, double area);

// The run as sweeps record it: {model, mu_peak (null without a peak), ux_peak, area_at_peak,
// area_normal, fz_normal, failed, message, unknowns, steps [contact_step_json, the layout of
// `contact --json`], validity}.
nlohmann::json scene_result_json(const SceneResult& r);

nlohmann::json contact_scene_json(const ContactScene& s);

// The default deepest penetration a converged FEM step may leave, m: 0.1 x the rms height of the
// ground (the dry surface, also when the obstacle is its wet version; ContactScene::max_penetration).
double default_max_penetration(const HeightMap& ground, int threads = 1);

// The spectral model's grid: `obstacle` resampled to the FEM's face lattice (obstacle spacing /
// refine, resample_triangulated), after checking that the solver's working set (about 24 doubles
// per grid point: maps, FFT buffers, CG vectors) fits this machine's memory (InputError --refine).
HeightMap spectral_lattice(const HeightMap& obstacle, int refine);

// The FEM's options for the scene on `obstacle` (periodic): the one mapping from a scene to the
// block's run, used by the scene's runs and by `contact`. The penetration limit's default (0)
// is 0.1 x the rms height of `ground` (the dry surface, also under a wet obstacle); negative
// switches the check off. `comm` MPI_COMM_NULL: PETSC_COMM_WORLD when the block is built.
// Throws InputError as check_fem_options.
ContactTestOptions fem_test_options(const ContactScene& s, const HeightMap& obstacle, const HeightMap& ground,
                                    MPI_Comm comm, const SceneRunHooks& hooks = {});

// The spectral model's options for the scene on `lattice` (the obstacle already resampled to
// the face lattice, resample_triangulated). Throws InputError as check_spectral_test_options.
SpectralTestOptions spectral_test_options(const ContactScene& s, const HeightMap& lattice);

}  // namespace wr
