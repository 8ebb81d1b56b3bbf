#include "app/scene_options.hpp"

#include <limits>

#include "lib/contact/contact_step.hpp"
#include "lib/core/errors.hpp"

namespace wr::app {
namespace {

// --thickness: metres or "inf" (half-space); empty gives 0 (the block height).
double parse_thickness(const std::string& text) {
  if (text.empty()) return 0;
  if (text == "inf") return std::numeric_limits<double>::infinity();
  std::size_t used = 0;
  double t = 0;
  try {
    t = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(t > 0)) throw InputError("--thickness", "must be a length > 0 in m, or inf");
  return t;
}

}  // namespace

void add_scene_options(CLI::App& s, SceneCli& c) {
  ContactScene& sc = c.scene;
  c.uz = s.add_option("--uz", sc.uz, "final downward displacement of the block's top face, m");
  c.ux = s.add_option("--ux", sc.ux, "final tangential displacement of the top face (shear), m");
  s.add_option("--steps", sc.normal_steps, "load steps of the normal phase")->capture_default_str();
  s.add_option("--shear-steps", sc.shear_steps, "load steps of the shear phase (0: as --steps)")->capture_default_str();
  s.add_flag("--to-peak", sc.to_peak,
             "fem shear: stop once the friction curve has turned over (a converged step " +
                 std::to_string(int(100 * kPeakFall + 0.5)) +
                 " % below the peak, or two below it: the static friction found), --ux being then the most the top "
                 "may move; steps start at --ux / --shear-steps and halve after a step twice as hard as the first one "
                 "(down to 1/8), never lengthen");
  s.add_option("--refine", sc.refine,
               "contact-face spacing = surface spacing / refine (fem mesh; spectral grid on the triangulated surface)")
      ->capture_default_str();
  s.add_option("--height", sc.height, "block height in m (0: the period, a cube; spectral: the layer thickness)")
      ->capture_default_str();
  s.add_option("--layers", sc.layers_per_level,
               "fem: brick layers at each in-plane spacing (more: softer, more accurate bulk; 4 converge it, 1 is too "
               "stiff: A/A0 at a given load ~25 % low at refine 1-2, see docs/validation.md)")
      ->capture_default_str();
  s.add_option("--coarsen", sc.max_coarsenings, "fem: in-plane spacing doublings allowed away from the face")
      ->capture_default_str();
  s.add_option("--E", sc.young, "Young's modulus, Pa (forces scale with it)")->capture_default_str();
  s.add_option("--nu", sc.poisson, "Poisson's ratio")->capture_default_str();
  s.add_option("--damping", sc.damping, "damping alpha_c of the geometry iteration (fem Signorini, spectral shear)")
      ->capture_default_str();
  s.add_option("--extrapolate", sc.extrapolate_every,
               "fem: Aitken jump along the slow mode (the face's creep) every N Signorini iterations; 0: off; not with "
               "--facet-normals (their iteration is not smooth)")
      ->capture_default_str();
  s.add_flag("--face-modes", sc.face_modes,
             "fem, fixed top, with --extrapolate: also jump along the face's slide, lateral expansion and twist "
             "(experimental)");
  s.add_option("--coarse-start", sc.coarse_refine,
               "fem: nested iteration; every step is solved first on a block of this refinement (below --refine, "
               "dividing it), and its increment starts the step on the fine block; 0: off (experimental)")
      ->capture_default_str();
  s.add_option("--max-penetration", sc.max_penetration,
               "fem: deepest penetration a converged step may leave, m (0: 0.1 x the rms height of the dry surface, "
               "also under water; negative: no check)")
      ->capture_default_str();
  s.add_option("--cutbacks", sc.cutbacks,
               "fem: a failed load step is retried from the last converged one in two halves, each halvable again, down "
               "to this many times (0 ... 8; 0: a failed step ends the run)")
      ->capture_default_str();
  s.add_option("--predictor", sc.predictor,
               "fem: which steps that continue the previous one's direction start from the last state extrapolated "
               "along the last increment (secant predictor): off, press (the normal steps; the default) or all (also "
               "the shear steps: faster, but it can reach the snap over the asperities earlier; see "
               "docs/fem-solver.md); off under --coarse-start")
      ->transform(CLI::CheckedTransformer(secant_predictor_names(), CLI::ignore_case))
      ->option_text("off|press|all (default press)");
  s.add_option("--ksp-rtol", sc.ksp_rtol, "fem: CG relative tolerance of a step's final linear solves")
      ->capture_default_str();
  s.add_option("--tol", sc.tolerance, "relative change of the face displacement that ends a step (fem; spectral shear)")
      ->capture_default_str();
  s.add_option("--spectral-tol", sc.spectral_tolerance,
               "spectral: relative l1 pressure change per iteration that ends a step (>= 1e-9: the CG runs in single "
               "precision, below it in double)")
      ->capture_default_str();
  s.add_option("--max-iterations", sc.max_iterations,
               "iterations allowed per step (0: the model's default: fem 300 Signorini iterations; spectral 5000 CG "
               "iterations, or 200 geometry iterations in a shear test)")
      ->capture_default_str();
  s.add_option("--iteration", sc.iteration,
               "fem: the geometry iteration of each load step: signorini (the thesis's Algorithm 1: damped fixed point, "
               "rays on the triangulated obstacle; linear convergence) or newton (Newton's method on the C2 spline "
               "through the same heights, curvature of the contact included; superlinear once the contact set settles; "
               "docs/fem-solver.md)")
      ->transform(CLI::CheckedTransformer(contact_iteration_names(), CLI::ignore_case))
      ->option_text("signorini|newton (default signorini)");
  s.add_option("--curvature", sc.curvature,
               "fem, --iteration newton: scale of the contact constraints' second-order term (1: Newton; 0: without it, "
               "a linearly converging Gauss-Newton iteration, for comparison)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  s.add_flag("--vertical", c.vertical, "fem: linearise once with vertical normals (small-slope approximation)");
  s.add_flag("--facet-normals", sc.facet_normals,
             "fem: constrain along the hit triangle's normal instead of the smooth vertex-normal blend");
  s.add_option("--facet-band", sc.facet_band,
               "with --facet-normals: blend into the smooth normal within this barycentric band of the triangle edges "
               "(0 ... 1; 0: pure facet normals)")
      ->capture_default_str();
  s.add_option("--block-normals", sc.block_normals,
               "experimental: constrain each node along the block's own deformed face normal (the thesis's reading of "
               "sec. 4.2.1) instead of the obstacle's, the normal relaxed by this factor per Signorini iteration "
               "(0 ... 1; 0: off). Not a physical model of a rigid frictionless obstacle: for comparison with the "
               "thesis only (docs/validation.md)")
      ->check(CLI::Range(0.0, 1.0))
      ->excludes("--facet-normals");
  s.add_option("--amg", c.amg,
               "fem: CG's AMG hierarchy: standard (smoothed aggregation), lean (unsmoothed aggregation, all-at-once "
               "products: ~5.3 instead of ~8.4 KiB per node, more CG iterations), or auto (lean only where standard "
               "would exceed 80 % of this host's memory)")
      ->capture_default_str();
  s.add_option("--solver", c.solver,
               "fem: linear solver of the active-set systems: direct (sparse Cholesky: SuiteSparse CHOLMOD on one "
               "rank, MUMPS on several), amg (CG with the AMG preconditioner of --amg), gmg (no matrix: CG with a "
               "geometric multigrid on the block's own coarser meshes, a fraction of AMG's memory; -gmg_* options "
               "through --petsc; not with --iteration newton), or auto (gmg from 20000 nodes, except for newton; "
               "else direct up to 20000 nodes on one rank when only pressing; AMG otherwise: docs/performance.md)")
      ->capture_default_str();
  s.add_option("--thickness", c.thickness,
               "spectral: layer thickness in m, or inf for a half-space (default: the block height)");
}

void finish_scene_options(SceneCli& c) {
  ContactScene& s = c.scene;
  s.thickness = parse_thickness(c.thickness);
  s.amg = parse_amg_hierarchy(c.amg, "--amg");
  s.solver = parse_linear_solver(c.solver, "--solver");
  s.follow_geometry = !c.vertical;
  if (s.shear_steps < 0) throw InputError("--shear-steps", "must be >= 1 (0: as --steps)");
  if (s.shear_steps == 0) s.shear_steps = s.normal_steps;
}

}  // namespace wr::app
