#include "lib/scene/contact_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/analytic/contact_theory.hpp"
#include "lib/contact/friction_convergence.hpp"
#include "lib/contact/periodic_obstacle.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/fem/block_press_shear.hpp"
#include "lib/spectral/spectral_press_shear.hpp"
#include "roads/height_stats.hpp"

namespace wr {

namespace {

// The scene's options of the block, without what depends on the obstacle (slope, penetration
// default) or on the run (communicator, outputs).
ContactTestOptions block_options(const ContactScene& s) {
  ContactTestOptions o;
  o.shear = s.shear;
  o.uz = s.uz;
  o.ux = s.ux;
  o.normal_steps = s.normal_steps;
  o.shear_steps = s.shear_steps;
  o.to_peak = s.to_peak;
  o.refine = s.refine;
  o.coarse_refine = s.coarse_refine;
  o.height = s.height;
  o.layers_per_level = s.layers_per_level;
  o.max_coarsenings = s.max_coarsenings;
  o.young = s.young;
  o.poisson = s.poisson;
  o.follow_geometry = s.follow_geometry;
  o.iteration = s.iteration;
  o.curvature = s.curvature;
  o.tolerance = s.tolerance;
  o.damping = s.damping;
  o.extrapolate_every = s.extrapolate_every;
  o.face_modes = s.face_modes;
  o.ksp_rtol = s.ksp_rtol;
  if (s.max_iterations > 0) o.max_iterations = s.max_iterations;
  o.max_cutbacks = s.cutbacks;
  o.secant_predictor = s.predictor;
  o.facet_normals = s.facet_normals;
  o.facet_band = s.facet_band;
  o.block_normals = s.block_normals;
  o.amg = s.amg;
  o.solver = s.solver;
  return o;
}

}  // namespace

void check_contact_scene(const ContactScene& s) {
  const bool spectral = s.model == ContactModel::spectral;
  if (s.to_peak && (s.model != ContactModel::fem || !s.shear))
    throw InputError("--to-peak", "shears the FEM block until mu turns over: needs --model fem and the shear problem");
  if (s.model == ContactModel::analytic && s.shear)
    throw InputError("--model", "the analytic model has no shear test; use fem or spectral");
  if (s.solver == LinearSolver::direct && s.iteration == ContactIteration::newton)
    throw InputError("--solver", "direct (Cholesky) needs positive definite systems; Newton's can be indefinite: "
                                 "use --solver amg or auto with --iteration newton");
  if (s.solver == LinearSolver::gmg && s.iteration == ContactIteration::newton)
    throw InputError("--solver", "gmg applies the stiffness without a matrix; Newton's systems (curvature blocks, "
                                 "possibly indefinite) need the assembled one: use --solver amg or auto with --iteration newton");
  if (!(s.pressure >= 0 && std::isfinite(s.pressure))) throw InputError("--pressure", "must be a finite pressure >= 0 Pa");
  const bool load_control = s.model != ContactModel::fem && s.pressure > 0;
  check_shared_contact_options({s.shear, !load_control, s.uz, s.ux, s.normal_steps, s.shear_steps, s.refine, s.young,
                                s.poisson, s.height, s.damping, s.tolerance, s.max_penetration, s.facet_band,
                                s.extrapolate_every, s.cutbacks});
  if (!(s.thickness >= 0)) throw InputError("--thickness", "must be a length > 0 m or inf");
  if (!(s.spectral_tolerance > 0 && s.spectral_tolerance < 1)) throw InputError("--spectral-tol", "must lie in (0, 1)");
  if (s.max_iterations < 0 || s.max_iterations > kMaxIterations)
    throw InputError("--max-iterations", "must be 0 (the model's default) ... " + std::to_string(kMaxIterations));
  if (s.threads < 0) throw InputError("--threads", "must be >= 0 (0: all hardware threads)");
  if (s.model == ContactModel::fem) {  // the block's own options, as the run will check them
    ContactTestOptions o = block_options(s);
    o.max_penetration = std::max(0.0, s.max_penetration);
    check_fem_options(o);
  }
  // The per-step records keep each iteration's residual: refuse a run whose worst case cannot fit.
  const int iterations = s.max_iterations > 0 ? s.max_iterations : (spectral ? 5000 : 300);
  require_memory(std::size_t(s.normal_steps + (s.shear ? s.shear_steps : 0)) * std::size_t(iterations), 2 * sizeof(double),
                 1.0, "--steps", "the step records of " + std::to_string(s.normal_steps + s.shear_steps) + " load steps");
}

namespace {

void summarise(SceneResult& r) {
  r.mu_peak = std::numeric_limits<double>::quiet_NaN();
  if (const ContactStep* p = peak_friction(r.steps)) {
    r.mu_peak = p->mu;
    r.ux_peak = p->ux;
    r.area_at_peak = p->area_fraction;
  }
  for (const auto& st : r.steps)
    if (st.ux == 0 && st.converged) {
      r.area_normal = st.area_fraction;
      r.fz_normal = st.fz;
    }
  if (r.failed && r.message.empty() && !r.steps.empty()) r.message = r.steps.back().message;
  if (r.failed && r.message.empty()) r.message = "contact run failed";
}

SceneResult run_fem(const HeightMap& obstacle, const ContactScene& s, MPI_Comm comm, const SceneRunHooks& hooks) {
  const ContactTestOptions o = fem_test_options(s, obstacle, hooks.ground ? *hooks.ground : obstacle, comm, hooks);
  if (hooks.on_setup) hooks.on_setup({obstacle.nx, obstacle.ny, obstacle.dx, o.rms_slope, 0.0});
  ContactTestResult t = run_contact_test(obstacle, o, hooks.on_step);
  SceneResult r;
  r.model = "fem";
  r.steps = t.steps;
  r.failed = t.failed;
  r.unknowns = t.nodes;
  r.wall_s = t.wall_s;
  r.fem = std::move(t);
  r.fem_options = o;
  return r;
}

SceneResult run_spectral(const HeightMap& obstacle, const ContactScene& s, const SceneRunHooks& hooks) {
  const HeightMap m = spectral_lattice(obstacle, s.refine);
  SpectralTestOptions o = spectral_test_options(s, m);
  o.face_maps = hooks.face_maps;
  if (hooks.on_setup)
    hooks.on_setup({m.nx, m.ny, m.dx, o.rms_slope, o.body.half_space() ? std::numeric_limits<double>::infinity() : o.body.thickness});
  SpectralTestResult t = run_spectral_contact_test(m, o, hooks.on_step);
  SceneResult r;
  r.model = "spectral";
  r.steps = t.steps;
  r.failed = t.failed;
  r.unknowns = t.nx * t.ny;
  r.wall_s = t.wall_s;
  r.spectral = std::move(t);
  r.spectral_options = o;
  return r;
}

}  // namespace

SceneResult run_contact_scene(const HeightMap& obstacle, const ContactScene& s, MPI_Comm comm,
                              const SceneRunHooks& hooks) {
  check_contact_scene(s);
  if (s.model == ContactModel::analytic) throw InputError("--model", "the analytic model has no contact scene to run");
  ContactRequest req;
  req.shear = s.shear;
  req.refine = s.model == ContactModel::fem ? s.refine : 0;
  req.rms_slope = rms_slope_finite_difference(obstacle, 1);
  req.e_star = s.young / (1 - s.poisson * s.poisson);
  auto checks = validity_checks(s.model, req);
  SceneResult r = s.model == ContactModel::fem ? run_fem(obstacle, s, comm, hooks) : run_spectral(obstacle, s, hooks);
  if (s.model == ContactModel::fem && s.shear) {
    checks.push_back(friction_convergence_check(r.steps));
    checks.push_back(friction_peak_check(r.steps));
  }
  r.validity = validity_json(s.model, checks, "user");
  summarise(r);
  return r;
}

SceneResult run_contact_scene_caught(const HeightMap& obstacle, const ContactScene& s, MPI_Comm comm,
                                     const SceneRunHooks& hooks) {
  try {
    return run_contact_scene(obstacle, s, comm, hooks);
  } catch (const std::exception& e) {
    SceneResult r;
    r.failed = true;
    r.model = model_name(s.model);
    r.message = e.what();
    r.mu_peak = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
}

std::vector<ContactStep> analytic_normal_curve(const ContactScene& s, double rms_slope, double area) {
  const double e_star = s.young / (1 - s.poisson * s.poisson);
  std::vector<ContactStep> steps;
  for (int k = 1; k <= s.normal_steps; ++k) {
    ContactStep st;
    const double p = s.pressure * double(k) / s.normal_steps;
    st.sigma_star = p / (e_star * rms_slope);
    st.area_fraction = persson_area_fraction(st.sigma_star);
    st.contact_area = st.area_fraction * area;
    st.fz = p * area;
    st.separation = std::numeric_limits<double>::quiet_NaN();
    st.converged = true;
    steps.push_back(st);
  }
  return steps;
}

nlohmann::json scene_result_json(const SceneResult& r) {
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& st : r.steps) steps.push_back(contact_step_json(st));
  // NaN (a failed run's missing peak) is not JSON: null instead.
  return {{"model", r.model},
          {"mu_peak", std::isfinite(r.mu_peak) ? nlohmann::json(r.mu_peak) : nlohmann::json(nullptr)},
          {"ux_peak", r.ux_peak},
          {"area_at_peak", r.area_at_peak},
          {"area_normal", r.area_normal},
          {"fz_normal", r.fz_normal},
          {"failed", r.failed},
          {"message", r.message},
          {"unknowns", r.unknowns},
          {"steps", steps},
          {"validity", r.validity}};
}

ContactTestOptions fem_test_options(const ContactScene& s, const HeightMap& obstacle, const HeightMap& ground,
                                    MPI_Comm comm, const SceneRunHooks& hooks) {
  ContactTestOptions o = block_options(s);
  o.rms_slope = rms_slope_finite_difference(obstacle, 1);
  // 0: the default; negative: no check.
  o.max_penetration = s.max_penetration > 0 ? s.max_penetration : s.max_penetration < 0 ? 0 : default_max_penetration(ground);
  o.comm = comm;
  o.face_maps = hooks.face_maps;
  o.vtu_path = hooks.vtu_path;
  o.checkpoint_path = hooks.checkpoint_path;
  o.restart_path = hooks.restart_path;
  o.progress_every_s = hooks.progress_every_s;
  o.trace = hooks.trace;
  check_fem_options(o);
  return o;
}

SpectralTestOptions spectral_test_options(const ContactScene& s, const HeightMap& lattice) {
  SpectralTestOptions o;
  o.uz = s.uz;
  o.pressure = s.pressure;
  o.steps = s.normal_steps;
  o.shear = s.shear;
  o.ux = s.ux;
  o.shear_steps = s.shear_steps;
  o.damping = s.damping;
  o.geometry_tolerance = s.tolerance;
  if (s.max_iterations > 0) (o.shear ? o.max_geometry_iterations : o.solver.max_iterations) = s.max_iterations;
  o.body.young = s.young;
  o.body.poisson = s.poisson;
  o.body.thickness = s.thickness > 0 ? s.thickness : s.height > 0 ? s.height : lattice.lx();
  o.solver.tolerance = s.spectral_tolerance;
  o.solver.threads = s.threads;
  o.solver.planning = s.planning;
  o.rms_slope = rms_slope_finite_difference(lattice, s.threads);
  check_spectral_test_options(o);
  return o;
}

HeightMap spectral_lattice(const HeightMap& obstacle, int refine) {
  constexpr double kDoublesPerPoint = 24;
  const std::size_t r = std::size_t(std::max(refine, 1));
  const std::size_t points = checked_cells(checked_cells(obstacle.nx, r, "--refine"), checked_cells(obstacle.ny, r, "--refine"), "--refine");
  require_memory(points, sizeof(double), kDoublesPerPoint, "--refine",
                 "the spectral model's " + std::to_string(obstacle.nx * r) + " x " + std::to_string(obstacle.ny * r) + " grid");
  return resample_triangulated(obstacle, refine);
}

double default_max_penetration(const HeightMap& ground, int threads) { return 0.1 * height_stats(ground, threads).sq; }

nlohmann::json contact_scene_json(const ContactScene& s) {
  return {{"model", model_name(s.model)}, {"shear", s.shear},
          {"uz", s.uz},
          {"ux", s.ux},
          {"normal_steps", s.normal_steps},
          {"shear_steps", s.shear_steps},
          {"to_peak", s.to_peak},
          {"refine", s.refine},
          {"E", s.young},
          {"nu", s.poisson},
          {"height", s.height},
          {"thickness", std::isfinite(s.thickness) ? nlohmann::json(s.thickness) : nlohmann::json("inf")},
          {"pressure", s.pressure},
          {"damping", s.damping},
          {"extrapolate_every", s.extrapolate_every},
          {"tolerance", s.tolerance},
          {"spectral_tolerance", s.spectral_tolerance},
          {"max_iterations", s.max_iterations},
          {"cutbacks", s.cutbacks},
          {"predictor", secant_predictor_name(s.predictor)},
          {"max_penetration", s.max_penetration},
          {"facet_normals", s.facet_normals},
          {"facet_band", s.facet_band},
          {"layers_per_level", s.layers_per_level},
          {"max_coarsenings", s.max_coarsenings},
          {"coarse_start", s.coarse_refine},
          {"face_modes", s.face_modes},
          {"ksp_rtol", s.ksp_rtol},
          {"follow_geometry", s.follow_geometry},
          {"iteration", contact_iteration_name(s.iteration)},
          {"curvature", s.curvature},
          {"block_normals", s.block_normals},
          {"amg", amg_hierarchy_name(s.amg)},
          {"solver", linear_solver_name(s.solver)}};
}

}  // namespace wr
