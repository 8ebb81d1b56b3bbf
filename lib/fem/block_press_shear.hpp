#pragma once
// The thesis's contact experiments on one scene (sec. 4.2.2): Problem A (normal load: the top
// face pushed down in steps) and Problem B (shear test: after A, the top pushed sideways in
// steps), on an elastic block whose side equals the obstacle's period. Per step: forces,
// friction ratio, contact fraction, normalised pressure, separation, penetration, iterations,
// wall time. A step whose solver fails is retried in halves (max_cutbacks) or ends the run;
// the finished steps are kept.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lib/contact/contact_step.hpp"
#include "lib/core/height_map.hpp"
#include "lib/fem/elastic_block.hpp"

namespace wr {

// The geometry iteration of each load step: the thesis's Algorithm 1 (damped fixed point with
// rays on the triangulated obstacle) or Newton's method on the C2 spline through the same
// heights (ContactLoad::smooth).
enum class ContactIteration { signorini, newton };
// The names the options take ("signorini", "newton"), in that order.
const std::vector<std::pair<std::string, ContactIteration>>& contact_iteration_names();
const char* contact_iteration_name(ContactIteration i);

// Which load steps start from the secant prediction (ContactTestOptions::secant_predictor).
enum class SecantPredictor { off, press, all };
// The names the options take ("off", "press", "all"), in that order.
const std::vector<std::pair<std::string, SecantPredictor>>& secant_predictor_names();
const char* secant_predictor_name(SecantPredictor p);

struct ContactTestOptions {
  bool shear = false;       // Problem B after A
  double uz = 0;            // m, final normal displacement of the top
  double ux = 0;            // m, final tangential displacement (shear)
  int normal_steps = 4;
  int shear_steps = 4;
  // Shear until the mu(ux) curve has turned over (peak_reached): the shear phase starts with
  // steps of ux / shear_steps and ends at the first converged step after the peak whose mu is
  // lower, or at ux (then the peak is only a lower bound, as without this). Each next step is
  // sized from the last one's Signorini iterations (adapt_shear_step).
  bool to_peak = false;
  int refine = 2;           // contact-face spacing = obstacle spacing / refine
  // > 0 (and < refine, dividing it): nested iteration. Every step is solved first on a block
  // with this refinement, and its increment, interpolated to this block's face and lifted into
  // it, starts the step here (ElasticBlock::add_lifted_face_field).
  int coarse_refine = 0;
  double height = 0;        // m, block height (0: the period, a cube)
  int layers_per_level = 2;  // brick layers at each in-plane spacing (graded_mesh.hpp)
  int max_coarsenings = 16;  // in-plane doublings of the spacing away from the face (0: none)
  double young = 1.0, poisson = 0.45;
  bool follow_geometry = true;
  ContactIteration iteration = ContactIteration::signorini;
  double curvature = 1.0;   // Newton: scale of the constraints' second-order term (ContactLoad)
  double damping = 0.8, tolerance = 1e-5;
  int extrapolate_every = 5;  // slow-mode jumps every this many Signorini iterations (0: off)
  bool face_modes = false;    // also jump along the face's rigid in-plane modes (ContactLoad)
  double ksp_rtol = 1e-7;   // CG relative tolerance of the final linearisation of a step
  double max_penetration = 0;  // m; > 0: a converged step leaving a deeper penetration fails
  int max_iterations = 300;  // Signorini iterations per step
  bool face_maps = false;    // keep contact-face maps per step (rank 0)
  bool trace = false;        // print every Signorini iteration (rank 0, stderr)
  double progress_every_s = 0;  // > 0: a progress line at most this often within a step (rank 0)
  bool facet_normals = false;  // constraint normals of the hit triangles instead of the smooth blend
  double facet_band = 0;       // > 0: PeriodicObstacle::banded_facet_normal with this band
  double block_normals = 0;    // > 0: constrain along the block's normal, relaxed so (ContactLoad)
  std::string vtu_path{};    // write the deformed block of the last step (.vtu), if set
  double rms_slope = 0;     // of the obstacle as triangulated (normalises sigma*, eq. 5.2); > 0
  MPI_Comm comm = MPI_COMM_NULL;  // the processes sharing the block (null: PETSC_COMM_WORLD)
  AmgHierarchy amg = AmgHierarchy::automatic;  // CG's AMG hierarchy (amg_hierarchy.hpp)
  LinearSolver solver = LinearSolver::automatic;  // sparse Cholesky or AMG (linear_solver.hpp)
  // Load-step cutbacks: a step that fails (not converged, or a node left too deep) is retried
  // from the last converged state in two halves, each of which may again be halved, down to
  // this many times (0 ... 8; 0: a failed step ends the run). Not with coarse_refine.
  int max_cutbacks = 0;
  // Secant predictor: a step that continues the previous one's direction (the second and later
  // steps of a phase) starts from the last converged state extrapolated along the last
  // increment, u_last + r (u_last - u_prev), r = the ratio of the increments, instead of from
  // u_last. Why: equal increments of a phase move the face by similar amounts, and the
  // Signorini iteration otherwise spends its iterations walking it there. `press` (the
  // default) predicts the normal steps only: there it reaches the same state in fewer
  // iterations (300 x 300 Problem A: the same Fz to 0.12 %, step 2 in 52 instead of 69
  // iterations). `all` predicts the shear steps too, which is faster but not neutral: a
  // frictionless shear on a rough obstacle is path dependent (the block snaps over its
  // asperities), and starting ahead on the secant crosses the snap earlier (1 cm stand-in: peak
  // mu 0.349 at 5.5 mm against 0.450 at 7 mm; docs/fem-solver.md). A coarse start (coarse_refine) chooses
  // the start itself, and the predictor then stays off.
  SecantPredictor secant_predictor = SecantPredictor::press;
  // Checkpoints (contact_checkpoint.hpp): written here after every converged load step when set;
  // a run with restart_path set continues from the checkpoint there (the same surface, options
  // and rank count), reporting the steps it holds as its own. Both may name one file. Its ux and
  // shear_steps may differ (not with to_peak): the shear goes on by extended_plan; so may the
  // cutbacks, tolerance and max_penetration of the steps to come (RestartableOptions).
  std::string checkpoint_path{};
  std::string restart_path{};
};

// One load state of the plan: the top's displacement and the halvings still allowed on the way
// to it from the state before.
struct LoadTarget {
  double uz = 0, ux = 0;  // m
  int cutbacks_left = 0;
};

// r > 0 when `next` continues the straight path prev -> last in its direction (next - last =
// r (last - prev)); 0 otherwise (a turn, as from the normal phase into the shear, or no step).
double continuation_ratio(const LoadTarget& prev, const LoadTarget& last, const LoadTarget& next);

// With ContactTestOptions::to_peak: the next shear increment (m) after a converged one of
// `last_step` m that took `iterations` Signorini iterations, `reference` those of the first
// shear step. A step more than twice as hard as the first is followed by one half as long
// (down to first / 8), any other by an equal one (`first`: ux / shear_steps). Why relative to
// the first step: on rough scenes a step's iterations hardly depend on its length (thesis
// scene, refine 1: 65 at 1 mm, 74 at 2 mm), so an absolute target would shrink the steps, and
// multiply the work, for nothing; a step much harder than the first one signals a snap ahead.
// Why never longer: a frictionless shear over asperities is path dependent (the block snaps
// over them), and a longer step can cross a snap the quasi-static path would not (saw-tooth
// test: 1.25 then 1.875 mm turned over at mu 0.14; steps of about 1.2 mm reached 0.25).
double adapt_shear_step(double last_step, int iterations, int reference, double first);

// The requested states in order: opt.normal_steps equal normal increments to uz, then (shear)
// opt.shear_steps equal tangential increments to ux at uz.
std::vector<LoadTarget> load_plan(const ContactTestOptions& opt);

// A restart's plan when it shears to another ux or in other steps than the checkpoint's run
// (not with to_peak): the old plan's converged targets (old[0, next)), then those of
// load_plan(opt) beyond `last`, the last converged state. Nothing beyond: plan.size() == next.
std::vector<LoadTarget> extended_plan(const std::vector<LoadTarget>& old, std::size_t next, const LoadTarget& last,
                                      const ContactTestOptions& opt);

// The options a restart may change, as the checkpoint's run had them (contact_checkpoint.hpp).
struct RestartableOptions {
  double ux = 0;  // m
  int shear_steps = 0, max_cutbacks = 0;
  double tolerance = 0, max_penetration = 0;  // -, m
};

// A restarted run: its checkpoint, the steps it kept, and the options they were solved with.
struct RestartRecord {
  std::string checkpoint;
  std::size_t steps_kept = 0;
  RestartableOptions kept_options;
};

struct ContactTestResult {
  std::size_t nodes = 0, dofs = 0, face_nodes = 0, elements = 0, mesh_points = 0;
  int layers = 0, coarsenings = 0;
  AmgHierarchy amg = AmgHierarchy::standard;  // the hierarchy the block used
  LinearSolver solver = LinearSolver::amg;    // the linear solver the block used
  double wall_setup = 0;  // s, mesh and assembly
  std::size_t face_nx = 0, face_ny = 0;  // face nodes per row, rows
  double face_spacing = 0, rms_slope = 0, e_star = 0;
  std::vector<ContactStep> steps;
  bool failed = false;
  double wall_s = 0;
  std::optional<RestartRecord> restart;  // set when restarted from a checkpoint
};


// --extrapolate's value: 0 (off) or a block of >= 2 Signorini iterations; InputError otherwise.
void check_extrapolation_block(int every);
// Load steps per phase and iterations per step allowed: far beyond any useful run, and small
// enough that the per-step records cannot outgrow the machine's memory.
constexpr int kMaxLoadSteps = 10000;
constexpr int kMaxIterations = 1000000;
// The options every contact run has, whichever model and driver (ContactTestOptions, the sweeps'
// ContactScene): checked in one place (InputError naming the option).
struct SharedContactOptions {
  bool shear = false;
  bool uz_required = true;  // false under load control (--pressure), where uz may be 0
  double uz = 0, ux = 0;
  int normal_steps = 1, shear_steps = 1, refine = 1;
  double young = 1, poisson = 0, height = 0, damping = 1, tolerance = 1e-4, max_penetration = 0, facet_band = 0;
  int extrapolate_every = 0, cutbacks = 0;
};
void check_shared_contact_options(const SharedContactOptions& o);
// Every FEM option at once (the shared ones above, then the FEM's own): the validator that
// `contact` and the sweeps' scenes both pass through, before any work.
void check_fem_options(const ContactTestOptions& opt);
// --cutbacks' value: 0 ... 8; InputError otherwise.
void check_cutbacks(int cutbacks);

// `obstacle` must be periodic. `on_step` (may be empty) is called after every step.
ContactTestResult run_contact_test(const HeightMap& obstacle, const ContactTestOptions& opt,
                                   const StepListener& on_step = {});

}  // namespace wr
