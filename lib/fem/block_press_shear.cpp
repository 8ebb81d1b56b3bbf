#include "lib/fem/block_press_shear.hpp"

#include <mpi.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "lib/contact/friction_convergence.hpp"
#include "lib/core/errors.hpp"
#include "lib/fem/contact_checkpoint.hpp"

namespace wr {
namespace {

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm == MPI_COMM_NULL ? PETSC_COMM_WORLD : comm, &r);  // as ElasticBlock's default
  return r;
}

// u_last + r (u_last - u_prev), with the contact set of the last state.
BlockState secant_start(const BlockState& last, const BlockState& prev, double r) {
  BlockState s = last;
  for (std::size_t i = 0; i < s.u.size(); ++i) s.u[i] += r * (last.u[i] - prev.u[i]);
  return s;
}

// The plan a restart goes on with: the checkpoint's, with the cutbacks of the steps to come
// shifted by the change of --cutbacks, or, when the shear's end or steps changed, extended_plan.
std::vector<LoadTarget> restart_plan(const ContactCheckpoint& c, const ContactTestOptions& opt) {
  if (opt.shear && !opt.to_peak && (c.options.ux != opt.ux || c.options.shear_steps != opt.shear_steps)) {
    std::vector<LoadTarget> plan = extended_plan(c.plan, c.next, c.last, opt);
    if (plan.size() == c.next) {
      char buf[160];
      std::snprintf(buf, sizeof buf, ": the checkpoint's run has reached ux %.6g m; a restart with --ux %.6g m has no step left",
                    c.last.ux, opt.ux);
      throw InputError("--restart", opt.restart_path + buf);
    }
    return plan;
  }
  std::vector<LoadTarget> plan = c.plan;
  for (std::size_t k = c.next; k < plan.size(); ++k)
    plan[k].cutbacks_left = std::max(0, plan[k].cutbacks_left + opt.max_cutbacks - c.options.max_cutbacks);
  return plan;
}

}  // namespace

double adapt_shear_step(double last_step, int iterations, int reference, double first) {
  const double ratio = double(iterations) / double(std::max(reference, 1));
  return std::max(ratio > 2 ? 0.5 * last_step : last_step, first / 8);
}

std::vector<LoadTarget> load_plan(const ContactTestOptions& opt) {
  std::vector<LoadTarget> plan;
  for (int k = 1; k <= opt.normal_steps; ++k) plan.push_back({opt.uz * k / opt.normal_steps, 0.0, opt.max_cutbacks});
  if (opt.shear)
    for (int k = 1; k <= opt.shear_steps; ++k) plan.push_back({opt.uz, opt.ux * k / opt.shear_steps, opt.max_cutbacks});
  return plan;
}

std::vector<LoadTarget> extended_plan(const std::vector<LoadTarget>& old, std::size_t next, const LoadTarget& last,
                                      const ContactTestOptions& opt) {
  std::vector<LoadTarget> plan(old.begin(), old.begin() + std::ptrdiff_t(std::min(next, old.size())));
  for (const LoadTarget& t : load_plan(opt)) {
    // The normal phase's targets are the old run's (uz and the normal steps are fingerprinted).
    const bool beyond = last.ux == 0 ? t.ux > 0 || t.uz > last.uz : t.ux > last.ux * (1 + 1e-12);
    if (beyond) plan.push_back(t);
  }
  return plan;
}

double continuation_ratio(const LoadTarget& prev, const LoadTarget& last, const LoadTarget& next) {
  const double az = last.uz - prev.uz, ax = last.ux - prev.ux;  // the last increment
  const double bz = next.uz - last.uz, bx = next.ux - last.ux;  // the coming one
  const double aa = az * az + ax * ax, dot = az * bz + ax * bx;
  if (!(aa > 0) || !(dot > 0)) return 0;
  // Parallel to rounding: the plan's targets are k/n fractions of the final load.
  const double cross = az * bx - ax * bz;
  if (std::abs(cross) > 1e-9 * aa) return 0;
  return dot / aa;
}

const std::vector<std::pair<std::string, SecantPredictor>>& secant_predictor_names() {
  static const std::vector<std::pair<std::string, SecantPredictor>> names{
      {"off", SecantPredictor::off}, {"press", SecantPredictor::press}, {"all", SecantPredictor::all}};
  return names;
}

const char* secant_predictor_name(SecantPredictor p) {
  for (const auto& [name, value] : secant_predictor_names())
    if (value == p) return name.c_str();
  return "?";
}

const std::vector<std::pair<std::string, ContactIteration>>& contact_iteration_names() {
  static const std::vector<std::pair<std::string, ContactIteration>> names{{"signorini", ContactIteration::signorini},
                                                                          {"newton", ContactIteration::newton}};
  return names;
}

const char* contact_iteration_name(ContactIteration i) {
  for (const auto& [name, value] : contact_iteration_names())
    if (value == i) return name.c_str();
  return "?";
}

void check_cutbacks(int cutbacks) {
  if (cutbacks < 0 || cutbacks > 8) throw InputError("--cutbacks", "must be 0 ... 8");
}

void check_extrapolation_block(int every) {
  if (every < 0 || every == 1) throw InputError("--extrapolate", "must be 0 (off) or a block of >= 2 Signorini iterations");
}

void check_shared_contact_options(const SharedContactOptions& o) {
  if (!std::isfinite(o.uz) || o.uz < 0) throw InputError("--uz", "must be a finite length >= 0 m");
  if (o.uz_required && !(o.uz > 0)) throw InputError("--uz", "the normal displacement must be > 0 m");
  if (!std::isfinite(o.ux) || (o.shear && !(o.ux > 0)))
    throw InputError("--ux", "must be a finite length (the shear test needs a tangential displacement > 0 m)");
  if (o.normal_steps < 1 || o.normal_steps > kMaxLoadSteps || (o.shear && (o.shear_steps < 1 || o.shear_steps > kMaxLoadSteps)))
    throw InputError("--steps", "must be 1 ... " + std::to_string(kMaxLoadSteps) + " per phase");
  if (o.refine < 1 || o.refine > 16) throw InputError("--refine", "must be 1 ... 16");
  // Beyond 1e12 Pa (diamond's modulus) forces and energies of road-sized blocks overflow doubles.
  if (!(o.young > 0 && o.young <= 1e12)) throw InputError("--E", "must be a modulus in (0, 1e12] Pa");
  if (!(o.poisson > -1 && o.poisson < 0.5)) throw InputError("--nu", "must lie in (-1, 0.5)");
  if (!(o.height >= 0 && std::isfinite(o.height))) throw InputError("--height", "must be a finite length >= 0 m (0: a cube)");
  if (!(o.damping > 0 && o.damping <= 2)) throw InputError("--damping", "must lie in (0, 2]");
  if (!(o.tolerance > 0 && o.tolerance < 1)) throw InputError("--tol", "must lie in (0, 1)");
  if (std::isnan(o.max_penetration))
    throw InputError("--max-penetration", "must be a length in m (0: 0.1 x the obstacle's rms height; negative: no check)");
  if (!(o.facet_band >= 0 && o.facet_band <= 1)) throw InputError("--facet-band", "must lie in [0, 1]");
  check_extrapolation_block(o.extrapolate_every);
  check_cutbacks(o.cutbacks);
}

void check_fem_options(const ContactTestOptions& o) {
  check_shared_contact_options({o.shear, true, o.uz, o.ux, o.normal_steps, o.shear_steps, o.refine, o.young, o.poisson,
                                o.height, o.damping, o.tolerance, o.max_penetration, o.facet_band,
                                o.extrapolate_every, o.max_cutbacks});
  if (o.layers_per_level < 1 || o.layers_per_level > 64) throw InputError("--layers", "must be 1 ... 64");
  if (o.max_coarsenings < 0) throw InputError("--coarsen", "must be >= 0");
  if (!(o.ksp_rtol > 0 && o.ksp_rtol < 1)) throw InputError("--ksp-rtol", "must lie in (0, 1)");
  if (o.max_iterations < 1 || o.max_iterations > kMaxIterations)
    throw InputError("--max-iterations", "must be 1 ... " + std::to_string(kMaxIterations));
  if (!(o.block_normals >= 0 && o.block_normals <= 1)) throw InputError("--block-normals", "must lie in [0, 1]");
  if (o.block_normals > 0 && o.facet_normals) throw InputError("--block-normals", "excludes --facet-normals");
  if (!(o.curvature >= 0 && o.curvature <= 1)) throw InputError("--curvature", "must lie in [0, 1]");
  if (o.iteration == ContactIteration::newton && (o.facet_normals || o.block_normals > 0))
    throw InputError("--iteration", "newton constrains along the smooth obstacle's normal: no --facet-normals or --block-normals");
  if (o.max_cutbacks > 0 && o.coarse_refine > 0)
    throw InputError("--cutbacks", "cannot be combined with --coarse-start (the coarse block's state is not rewound)");
  if (o.coarse_refine < 0 || (o.coarse_refine > 0 && (o.coarse_refine >= o.refine || o.refine % o.coarse_refine)))
    throw InputError("--coarse-start", "must be 0 (off) or a refinement below --refine that divides it");
  if ((!o.checkpoint_path.empty() || !o.restart_path.empty()) && o.coarse_refine > 0)
    throw InputError(o.restart_path.empty() ? "--checkpoint" : "--restart",
                     "cannot be combined with --coarse-start (the coarse block's state is not kept)");
  if (!o.restart_path.empty() && !std::filesystem::exists(o.restart_path))
    throw InputError("--restart", o.restart_path + ": no such checkpoint");
}

ContactTestResult run_contact_test(const HeightMap& obstacle, const ContactTestOptions& opt,
                                   const StepListener& on_step) {
  if (!obstacle.periodic) throw InputError("--surface", "the obstacle must be a periodic surface");
  check_fem_options(opt);
  if (!(opt.rms_slope > 0)) throw InputError("--surface", "the obstacle has no slope (flat surface)");

  const double t_start = MPI_Wtime();
  ContactTestResult res;
  HeightMap shifted = obstacle;  // highest point at z = 0: the block starts touching it
  const double hmax = *std::max_element(shifted.h.begin(), shifted.h.end());
  for (double& v : shifted.h) v -= hmax;
  const PeriodicObstacle ob(shifted);
  std::unique_ptr<SmoothObstacle> smooth;
  if (opt.iteration == ContactIteration::newton && opt.follow_geometry) smooth = std::make_unique<SmoothObstacle>(shifted);

  auto block_spec = [&](int refine) {
    BlockSpec b;
    b.mesh.lx = obstacle.lx();
    b.mesh.ly = obstacle.ly();
    b.mesh.lz = opt.height > 0 ? opt.height : b.mesh.lx;
    b.mesh.nx = int(obstacle.nx) * refine;
    b.mesh.ny = int(obstacle.ny) * refine;
    b.mesh.layers_per_level = opt.layers_per_level;
    b.mesh.max_coarsenings = opt.max_coarsenings;
    b.young = opt.young;
    b.poisson = opt.poisson;
    b.comm = opt.comm;
    b.amg = opt.amg;
    // automatic: by the block's size and use (linear_solver.hpp).
    b.solver = opt.solver;
    b.use = {opt.shear, opt.iteration == ContactIteration::newton};
    return b;
  };
  const BlockSpec b = block_spec(opt.refine);
  res.face_spacing = obstacle.dx / opt.refine;
  ElasticBlock block(b);
  std::unique_ptr<ElasticBlock> coarse;
  const BlockSpec bc = block_spec(std::max(opt.coarse_refine, 1));
  if (opt.coarse_refine > 0) coarse = std::make_unique<ElasticBlock>(bc);
  std::vector<double> coarse_face;  // the coarse block's face displacement after its last step
  if (coarse) coarse_face = coarse->face_displacement();
  res.wall_setup = MPI_Wtime() - t_start;
  res.nodes = block.nodes();
  res.dofs = block.dofs();
  res.mesh_points = std::size_t(block.mesh().mesh_points());
  res.elements = std::size_t(block.mesh().elements());
  res.layers = block.mesh().layers();
  res.coarsenings = block.mesh().coarsenings();
  res.amg = block.amg_hierarchy();
  res.solver = block.linear_solver();
  // Before a run of hours, say what it holds: the mesh and the hierarchy that decides its memory.
  if ((opt.progress_every_s > 0 || opt.trace) && rank_of(opt.comm) == 0) {
    if (res.solver == LinearSolver::gmg)
      std::fprintf(stderr, "  block: %zu nodes, %zu dofs, matrix-free, geometric multigrid: %s; set up in %.1f s\n",
                   res.nodes, res.dofs, block.multigrid_description().c_str(), res.wall_setup);
    else if (res.solver == LinearSolver::direct)
      std::fprintf(stderr, "  block: %zu nodes, %zu dofs, sparse Cholesky (direct solver), set up in %.1f s\n", res.nodes,
                   res.dofs, res.wall_setup);
    else
      std::fprintf(stderr, "  block: %zu nodes, %zu dofs, %s AMG hierarchy (about %.1f GiB in all), set up in %.1f s\n",
                   res.nodes, res.dofs, amg_hierarchy_name(res.amg),
                   fem_memory_estimate(double(res.nodes), res.amg) / 1073741824.0, res.wall_setup);
  }
  res.face_nodes = std::size_t(b.mesh.nx + 1) * (b.mesh.ny + 1);
  res.rms_slope = opt.rms_slope;
  res.e_star = opt.young / (1 - opt.poisson * opt.poisson);
  const double a0 = b.mesh.lx * b.mesh.ly;

  ContactLoad load;
  load.obstacle = &ob;
  load.follow_geometry = opt.follow_geometry;
  load.damping = opt.damping;
  load.extrapolate_every = opt.extrapolate_every;
  load.face_mode_extrapolation = opt.face_modes;
  load.tolerance = opt.tolerance;
  load.max_penetration = opt.max_penetration;
  load.ksp_rtol = opt.ksp_rtol;
  load.max_outer_iterations = opt.max_iterations;
  load.face_maps = opt.face_maps;
  load.trace = opt.trace;
  load.progress_every_s = opt.progress_every_s;
  load.facet_normals = opt.facet_normals;
  load.facet_band = opt.facet_band;
  load.block_normals = opt.block_normals;
  load.smooth = smooth.get();
  load.curvature = opt.curvature;
  res.face_nx = std::size_t(b.mesh.nx + 1);
  res.face_ny = std::size_t(b.mesh.ny + 1);
  std::vector<LoadTarget> plan = load_plan(opt);
  LoadTarget last{0, 0, 0};             // the last converged state (the unloaded block at first)
  // A coarse start chooses the start itself.
  const bool predict = opt.secant_predictor != SecantPredictor::off && !coarse;
  const bool keep_states = opt.max_cutbacks > 0 || predict;  // only these look back
  BlockState last_state = keep_states ? block.state() : BlockState{};
  LoadTarget prev{0, 0, 0};             // the converged state before `last` (predictor)
  BlockState prev_state;                // empty until two states are known
  double wasted_s = 0;                  // wall time of failed attempts, charged to the next step
  int failed_attempts = 0;
  int first_shear_iterations = 0;       // to_peak: the reference of adapt_shear_step
  std::size_t k_start = 0;
  const std::uint64_t fingerprint =
      opt.checkpoint_path.empty() && opt.restart_path.empty() ? 0 : contact_fingerprint(obstacle, opt);
  if (!opt.restart_path.empty()) {
    ContactCheckpoint c = read_contact_checkpoint(opt.restart_path, fingerprint, block.comm());
    k_start = c.next;
    res.restart = RestartRecord{opt.restart_path, c.steps.size(), c.options};
    plan = restart_plan(c, opt);
    last = c.last;
    prev = c.prev;
    first_shear_iterations = c.first_shear_iterations;
    block.restore(c.last_state);
    if (keep_states) last_state = std::move(c.last_state);
    if (predict) prev_state = std::move(c.prev_state);
    res.steps = std::move(c.steps);
    if ((opt.trace || opt.progress_every_s > 0) && rank_of(opt.comm) == 0)
      std::fprintf(stderr, "  restarted from %s: %zu converged steps, at uz %.4g m, ux %.4g m; %zu steps to go\n",
                   opt.restart_path.c_str(), res.steps.size(), last.uz, last.ux, plan.size() - k_start);
    if (on_step)
      for (const ContactStep& st : res.steps) on_step(st);
  }
  // After each converged step: the state a restart continues from.
  auto checkpoint = [&](std::size_t next) {
    if (opt.checkpoint_path.empty()) return;
    ContactCheckpoint c;
    c.fingerprint = fingerprint;
    c.options = {opt.ux, opt.shear_steps, opt.max_cutbacks, opt.tolerance, opt.max_penetration};
    c.next = next;
    c.plan = plan;
    c.last = last;
    c.prev = prev;
    c.first_shear_iterations = first_shear_iterations;
    c.steps = res.steps;
    c.last_state = keep_states ? last_state : block.state();
    c.prev_state = prev_state;
    write_contact_checkpoint(opt.checkpoint_path, c, block.comm());
  };
  for (std::size_t k = k_start; k < plan.size(); ++k) {
    load.uz = plan[k].uz;
    load.ux = plan[k].ux;
    const double t0 = MPI_Wtime();
    ContactStep st;
    // `press` predicts only steps without a tangential increment (the normal phase).
    const bool predict_this = opt.secant_predictor == SecantPredictor::all || plan[k].ux == last.ux;
    if (predict && predict_this && !prev_state.u.empty()) {
      st.predictor_ratio = continuation_ratio(prev, last, plan[k]);
      if (st.predictor_ratio > 0) block.restore(secant_start(last_state, prev_state, st.predictor_ratio));
    }
    if (coarse) {
      ContactLoad cl = load;
      cl.face_maps = false;
      if (opt.trace && rank_of(opt.comm) == 0) std::fprintf(stderr, "  step %d on the coarse block (refine %d):\n", int(k + 1), opt.coarse_refine);
      const ContactSolution cs = coarse->solve(cl);
      st.coarse_iterations = cs.outer_iterations;
      st.coarse_converged = cs.converged;
      st.coarse_wall_s = MPI_Wtime() - t0;
      // Only a converged coarse step is a start worth taking; either way the fine step decides.
      std::vector<double> now = coarse->face_displacement();
      if (cs.converged) {
        for (std::size_t q = 0; q < now.size(); ++q) coarse_face[q] = now[q] - coarse_face[q];
        block.add_lifted_face_field(coarse_face, bc.mesh.nx, bc.mesh.ny);
      }
      coarse_face = std::move(now);
      if (opt.trace && rank_of(opt.comm) == 0)
        std::fprintf(stderr, "  coarse step %d: %s in %d Signorini iterations, %.1f s; the fine step starts from it\n", int(k + 1),
                     cs.converged ? "converged" : "NOT converged", cs.outer_iterations, st.coarse_wall_s);
    }
    ContactSolution s = block.solve(load);
    if (opt.trace && rank_of(opt.comm) == 0 && res.solver == LinearSolver::gmg)
      std::fprintf(stderr, "  multigrid so far: %s\n", block.multigrid_timing().c_str());
    st.uz = load.uz;
    st.ux = load.ux;
    st.fz = s.fz;
    st.fx = s.fx;
    st.fy = s.fy;
    st.area_fraction = double(s.contact_nodes) / double(s.face_nodes);
    st.contact_area = st.area_fraction * a0;
    st.sigma_star = s.fz / a0 / (res.e_star * res.rms_slope);
    st.mu = s.fz > 0 ? s.fx / s.fz : 0.0;
    st.separation = s.mean_separation;
    st.max_penetration = s.max_penetration;
    st.penetration_x = s.deepest_at.x;
    st.penetration_y = s.deepest_at.y;
    st.nodes_over_penetration = s.nodes_over_penetration;
    st.signorini_iterations = s.outer_iterations;
    st.active_set_iterations = s.active_set_iterations;
    st.linear_iterations = s.linear_iterations;
    st.extrapolations = s.extrapolations;
    st.rejected_jumps = s.rejected_jumps;
    st.wall_s = MPI_Wtime() - t0;
    st.wall_linearise = s.wall_linearise;
    st.wall_rotate = s.wall_rotate;
    st.wall_solve = s.wall_solve;
    st.converged = s.converged;
    st.message = s.message;
    if (s.converged && opt.max_penetration > 0 && s.max_penetration > opt.max_penetration) {
      // Converged by the change criterion, yet a node sits visibly inside the obstacle: the
      // tolerance was too loose for this scene. Never report that as a result.
      st.converged = false;
      // Where and how widely: the obstacle's slope there says whether a steep flank is to blame.
      const Vec3 n = ob.normal(s.deepest_at.x, s.deepest_at.y);
      char buf[480];
      std::snprintf(buf, sizeof buf,
                    "penetration %.3g m left at x %.3f mm, y %.3f mm (obstacle slope %.2f there; %zu face node%s deeper "
                    "than the allowed %.3g m, --max-penetration); tighten --tol, or allow smaller steps (--cutbacks); "
                    "a run with --checkpoint may go on with --restart and a looser --max-penetration, its nodes then "
                    "that deep in the obstacle",
                    s.max_penetration, 1e3 * s.deepest_at.x, 1e3 * s.deepest_at.y, std::hypot(n.x, n.y) / n.z,
                    s.nodes_over_penetration, s.nodes_over_penetration == 1 ? "" : "s", opt.max_penetration);
      st.message = buf;
    }
    if (!st.converged && plan[k].cutbacks_left > 0) {
      // Load-step cutback: back to the last converged state, and the way there in two halves.
      if (rank_of(opt.comm) == 0 && (opt.trace || opt.progress_every_s > 0))
        std::fprintf(stderr, "  step to uz %.4g m, ux %.4g m failed after %d Signorini iterations and %.0f s (%s); "
                     "retrying it in two halves from uz %.4g m, ux %.4g m\n",
                     load.uz, load.ux, st.signorini_iterations, MPI_Wtime() - t0, st.message.c_str(), last.uz, last.ux);
      block.restore(last_state);
      wasted_s += MPI_Wtime() - t0;
      ++failed_attempts;
      --plan[k].cutbacks_left;
      const LoadTarget half{(last.uz + plan[k].uz) / 2, (last.ux + plan[k].ux) / 2, plan[k].cutbacks_left};
      plan.insert(plan.begin() + std::ptrdiff_t(k), half);
      --k;  // the loop's ++k lands on the half step
      continue;
    }
    st.wall_s += wasted_s;
    st.failed_attempts = std::exchange(failed_attempts, 0);
    wasted_s = 0;
    st.history = std::move(s.history);
    // Friction is only asked of shear steps; a normal step's Fx is a by-product.
    if (load.ux != 0 && opt.follow_geometry) st.mu_drift = friction_drift(s.mu_history, s.damping_history, opt.damping);
    st.mu_history = std::move(s.mu_history);
    st.face_pressure = std::move(s.face_pressure);  // maps can be large: move, do not copy
    st.face_gap = std::move(s.face_gap);
    st.face_status = std::move(s.face_status);
    fail_if_not_finite(st);
    res.steps.push_back(st);
    if (on_step) on_step(st);
    if (!st.converged) {
      res.failed = true;
      break;
    }
    const double step_ux = plan[k].ux - last.ux;
    prev = std::exchange(last, plan[k]);
    if (predict) prev_state = std::move(last_state);
    if (keep_states) last_state = block.state();
    if (opt.to_peak && opt.shear && step_ux > 0) {
      if (peak_reached(res.steps)) {  // the curve turned over: the static friction is found
        plan.resize(k + 1);
        checkpoint(k + 1);
        break;
      }
      if (first_shear_iterations == 0) first_shear_iterations = s.outer_iterations;
      // The rest of the shear phase, re-planned from here: one step, sized by this one's work.
      plan.erase(plan.begin() + std::ptrdiff_t(k) + 1, plan.end());
      const double first = opt.ux / opt.shear_steps;
      const double next =
          std::min(opt.ux, last.ux + adapt_shear_step(step_ux, s.outer_iterations, first_shear_iterations, first));
      if (next > last.ux * (1 + 1e-12)) plan.push_back({opt.uz, next, opt.max_cutbacks});
      if ((opt.trace || opt.progress_every_s > 0) && rank_of(opt.comm) == 0 && plan.size() > k + 1)
        std::fprintf(stderr, "  shear to the peak: mu %.4f at ux %.4g m; next step to ux %.4g m\n", st.mu, last.ux, next);
    }
    checkpoint(k + 1);
  }
  if (!opt.vtu_path.empty()) block.write_vtu(opt.vtu_path);
  res.wall_s = MPI_Wtime() - t_start;
  return res;
}


}  // namespace wr
