#include "lib/fem/elastic_block_impl.hpp"

namespace wr {

using petsc::check;

ContactSolution ElasticBlock::solve(const ContactLoad& load) {
  Impl& m = *impl_;
  ContactSolution out;
  out.face_nodes = std::size_t(m.face_nx() + 1) * (m.face_ny() + 1);
  std::vector<FaceNode> face = m.owned_face_nodes();
  if (m.active.size() != face.size()) m.active.assign(face.size(), 0);
  const Impl::TopBoundary top = m.prescribe_top(load);
  // Newton on the C2 obstacle (ContactLoad::smooth): full steps, none of the fixed-point
  // iteration's devices (damping, jumps). Its systems can be indefinite (the softening part of
  // the constraints' curvature): CG detects that and the cut is applied, where a Cholesky
  // factorisation would fail (CHOLMOD) or hide it (MUMPS's LDL^T). So Newton takes the AMG.
  const bool newton = load.follow_geometry && load.smooth;
  if (newton && m.solver == LinearSolver::gmg)
    throw std::runtime_error("Newton's iteration needs the assembled stiffness (its systems can be indefinite): "
                             "use --solver amg with --iteration newton");
  Impl::LinearSystems s(m.comm, m.u, out.face_nodes, m.amg, newton ? LinearSolver::amg : m.solver, m.gmg.get());

  // Facet normals make the iteration's map discontinuous (nodes chatter across the kinks), which
  // Aitken's smooth geometric model does not fit: on the demo's 70 % coverage scene the jumps led
  // a shear step to a state 1.4x deeper in the obstacle than allowed. Blend normals only.
  if (newton && m.lambda.size() != face.size()) m.lambda.assign(face.size(), 0.0);
  Impl::CurvatureScales curvature;
  curvature.on = newton;
  curvature.all = std::clamp(load.curvature, 0.0, 1.0);
  curvature.negative = m.softening_scale;
  const bool smooth_map = load.follow_geometry && load.obstacle && !load.facet_normals && !newton;
  SlowModeExtrapolation extrapolation(m.u, smooth_map ? load.extrapolate_every : 0);
  // The face's in-plane rigid modes under a fixed top (FaceModeExtrapolation).
  const bool modes_on = smooth_map && load.top == TopCondition::fixed && load.face_mode_extrapolation;
  FaceModeExtrapolation face_extrapolation(modes_on ? load.extrapolate_every : 0);
  const FaceModeBasis basis(*m.mesh, m.spec.mesh.lx, m.spec.mesh.ly, m.face_nx(), m.face_ny(), modes_on);

  constexpr double kLeastReduction = 0.1;  // of a loose linearisation's first CG residual
  // A slow-mode jump is undone when the linearisation at the jumped iterate loses more than
  // this fraction of the contact nodes. Why: the creep moves the face along the obstacle and
  // barely changes the contact set (jumps that paid off lost 0.6-1.7 % of it on the 50 x 50 and
  // 300 x 300 scenes), while jumps that overshot into the fast modes opened it (300 x 300:
  // 98k -> 78k and 197k -> 133k nodes, each followed by many iterations of recovery).
  constexpr double kMaxContactLoss = 0.1;
  // A jump is also undone when the correction after it shows it overshot (jump_overshot).
  std::size_t contact_before_jump = 0;  // > 0: the last iteration jumped
  double change_before_jump = 0;        // > 0: the last iteration jumped, at this change
  PenetrationRetries penetration_retries;
  bool retrying = false;  // the last iteration passed the change test and went on for a node too deep
  const int outer_max = load.follow_geometry ? load.max_outer_iterations : 1;
  AdaptiveDamping damping(load.damping);
  std::vector<double> normal_force(face.size(), 0.0);  // N, per face node, last linearisation
  std::vector<double> prev_corr(3 * face.size(), 0.0);
  // Back to the iterate before the last jump; both extrapolations measure afresh from there.
  const auto undo_jump = [&] {
    check(VecCopy(s.before_jump, m.u), "VecCopy");
    extrapolation.restart(m.u);
    if (modes_on) face_extrapolation.restart(m.face_mode_coordinates(face, basis));
    ++out.rejected_jumps;
    contact_before_jump = 0;
    change_before_jump = 0;
  };
  bool final_pass = false;
  double loose_factor = 0.01;  // CG rtol of a loose solve = loose_factor x smallest_change
  double smallest_change = INFINITY;  // of this step's Signorini iterations so far
  const double t_solve_start = MPI_Wtime();
  double last_progress = t_solve_start;
  for (int outer = 0; outer < outer_max; ++outer) {
    out.outer_iterations = outer + 1;
    // 1. Linearise the contact at the current configuration.
    double t_phase = MPI_Wtime();
    m.linearise(face, load);
    out.wall_linearise += MPI_Wtime() - t_phase;
    t_phase = MPI_Wtime();

    // 2. Rotate the face nodes into their constraint frames: Khat = R^T K R, uh = R^T u.
    int clipped = 0;
    const double unit_diag = m.rotate_into_frames(face, s, curvature, clipped);
    if (newton) MPI_Allreduce(&clipped, &out.clipped_nodes, 1, MPI_INT, MPI_SUM, m.comm);
    out.wall_rotate += MPI_Wtime() - t_phase;
    t_phase = MPI_Wtime();

    // 3. Primal-dual active set on the bounds uh_z >= g at the face nodes. Early
    // linearisations are only approximations of the final one: solve them loosely (CG
    // tolerance a hundredth of the smallest relative change of the step so far), tightening
    // to ksp_rtol at the end. Why the smallest and not the last: a loose solve under-reports
    // the change (CG, warm-started, stops before it has moved u all the way), so a tolerance
    // tied to the last change alternated: on the 300 x 300 obstacle a solve at rtol 5e-5
    // (~15 CG) reported 2e-3, which made the next tight (2e-5, ~30 CG, 6e-3), and so on; the
    // alternating block changes then fooled the slow-mode jump into a factor-11 overshoot.
    // A running minimum only ever tightens, so it cannot feed back.
    double rtol = load.ksp_rtol;
    if (load.inexact && load.follow_geometry && load.obstacle && !final_pass)
      rtol = std::clamp(out.history.empty() ? 1e-3 : loose_factor * smallest_change, load.ksp_rtol, 1e-3);
    check(KSPSetTolerances(s.ksp, rtol, 1e-300, PETSC_DEFAULT, 20000), "KSPSetTolerances");
    Impl::ActiveSetControl control;
    control.unit_diag = unit_diag;
    // The first system of a loose linearisation must at least cut its residual tenfold (see
    // LeastReductionTest); the active-set corrections after it start close to their answer.
    control.loose = rtol > load.ksp_rtol;
    if (control.loose) set_convergence_test(s.ksp, kLeastReduction);
    control.accept_unsettled = load.follow_geometry && load.obstacle && !final_pass;
    control.max_iterations = control.accept_unsettled
                                 ? std::min(load.early_active_set_iterations, load.max_active_set_iterations)
                                 : load.max_active_set_iterations;
    control.reuse_preconditioner = load.reuse_preconditioner;
    const Impl::ActiveSetOutcome as = m.solve_active_set(face, top, s, control, out);
    if (!as.ok && newton && curvature.negative > 0 && curvature.all > 0 &&
        out.message.rfind("linear solve failed", 0) == 0) {
      // CG met an indefinite system: the softening curvature outweighed the stiffness somewhere
      // (multipliers of an early iteration, or a node perched on a sharp peak). Repeat this
      // iteration with less of it, and keep it so. Why not let it grow back after definite
      // solves (the first version doubled it each time): the next growth met an indefinite
      // system again, every second or third iteration, and an iteration whose quadratic model
      // changes from one step to the next converges like none of them. 100 x 100 thesis-like
      // scene, refine 1, uz 3 mm in 2 steps: 43 + 59 iterations growing back, 21 + 20 kept
      // (Algorithm 1: 38 + 51); docs/fem-solver.md.
      curvature.negative = curvature.negative > 0.01 ? 0.25 * curvature.negative : 0.0;
      m.softening_scale = curvature.negative;
      ++out.curvature_cuts;
      if (load.trace && m.rank == 0)
        std::fprintf(stderr, "    %s: softening curvature scaled by %.3g\n", out.message.c_str(), curvature.negative);
      out.message.clear();
      continue;
    }
    if (!as.ok) {
      if (out.message.empty())
        out.message = "active set still changing after " + std::to_string(load.max_active_set_iterations) +
                      " iterations in Signorini iteration " + std::to_string(outer + 1);
      break;
    }
    double ct = double(as.contact), ctot;
    MPI_Allreduce(&ct, &ctot, 1, MPI_DOUBLE, MPI_SUM, m.comm);
    out.contact_nodes = std::size_t(ctot);
    out.wall_solve += MPI_Wtime() - t_phase;
    const std::size_t contact_then = std::exchange(contact_before_jump, 0);
    if (contact_then > 0 && double(out.contact_nodes) < (1 - kMaxContactLoss) * double(contact_then)) {
      undo_jump();
      if (load.trace && m.rank == 0)
        std::fprintf(stderr, "    slow-mode jump undone: %zu of %zu contact nodes left\n", out.contact_nodes,
                     contact_then);
      continue;  // re-linearise where the jump started
    }
    {
      const PetscScalar* ra;
      VecGetArrayRead(s.r, &ra);
      for (std::size_t n = 0; n < face.size(); ++n)
        normal_force[n] = m.active[n] ? ra[face[n].row[2] - 3 * PetscInt(m.own_begin)] : 0.0;
      VecRestoreArrayRead(s.r, &ra);
      // The force is lambda grad g and |grad g| = 1 / N_z.
      if (newton)
        for (std::size_t n = 0; n < face.size(); ++n) m.lambda[n] = normal_force[n] * face[n].normal.z;
    }

    // 4. Next iterate: a damped step towards the linearised solution u*. Convergence measure:
    // the correction u* - u on the contact face relative to u* there (the l2 norm over the face
    // nodes = the lumped boundary mass norm on the uniform face).
    check(VecCopy(s.uh, s.ustar), "VecCopy");
    m.stiffness->rotate_vector(s.ustar, s.q_all, false);
    const Impl::Correction corr = m.measure_correction(face, s.ustar, prev_corr);
    const double change = corr.change;
    if (const double before = std::exchange(change_before_jump, 0.0);
        jump_overshot(change, before)) {
      undo_jump();
      if (load.trace && m.rank == 0)
        std::fprintf(stderr, "    slow-mode jump undone: change %.2e after it, %.2e before\n", change, before);
      continue;  // re-linearise where the jump started
    }
    const bool damped = load.follow_geometry && !newton;
    if (damped) damping.after_correction(corr.cosine);
    out.history.push_back(change);
    smallest_change = std::min(smallest_change, change);
    if (damped) damping.after_change(out.history);
    const double alpha = damped ? damping.alpha() : 1.0;
    const double step_change = damped ? damping.step_change(change) : change;
    check(VecScale(m.u, 1 - alpha), "VecScale");
    check(VecAXPY(m.u, alpha, s.ustar), "VecAXPY");
    const auto forces = m.top_forces(s.ustar, top, s.r);
    const double trace_fx = forces[0], trace_fz = forces[2];
    out.mu_history.push_back(trace_fz > 0 ? trace_fx / trace_fz : 0.0);
    out.damping_history.push_back(alpha);
    // The deepest node of the new iterate and of the linearised solution u* (vertical depth
    // below the obstacle), collective: only when tracing, since each is one more pass over the face.
    const bool trace_depths = load.trace && load.obstacle;
    const double trace_pen = trace_depths ? m.deepest_penetration(face, m.u, load) : 0.0;
    const double trace_pen_star = trace_depths ? m.deepest_penetration(face, s.ustar, load) : 0.0;
    char newton_state[64] = "";
    if (newton)
      std::snprintf(newton_state, sizeof newton_state, "  curv- %.3g clipped %d", curvature.negative, out.clipped_nodes);
    if (load.trace && m.rank == 0)
      std::fprintf(stderr,
                   "    %s %3d  change %.3e  alpha %.3f  contact %zu%s  pdas %d  cg %d  rtol %.0e  Fz %.6e  Fx %.6e  pen %.2e  pen* %.2e%s  [%.1f s]\n",
                   newton ? "newton" : "signorini", outer + 1, change, alpha, out.contact_nodes, as.settled ? "" : "+",
                   out.active_set_iterations, out.linear_iterations, rtol, trace_fz, trace_fx, trace_pen, trace_pen_star,
                   newton_state,
                   MPI_Wtime() - t_solve_start);
    if (!load.trace && load.progress_every_s > 0 && m.rank == 0 &&
        MPI_Wtime() - last_progress >= load.progress_every_s) {
      last_progress = MPI_Wtime();
      std::fprintf(stderr, "    ... Signorini iteration %d: change %.2e (tolerance %.1e, damping %.2f), %zu nodes in contact, %.0f s\n",
                   outer + 1, step_change, load.tolerance, alpha, out.contact_nodes, last_progress - t_solve_start);
    }
    out.final_damping = alpha;

    // 5. Slow-mode jumps (judged by the next linearisation, above); then the convergence test
    // of Algorithm 1, with its confirmations.
    if (const double jump = extrapolation.after_iteration(m.u, s.before_jump); jump > 0) {
      contact_before_jump = out.contact_nodes;
      change_before_jump = change;
      out.extrapolations = extrapolation.jumps() + face_extrapolation.jumps();
      if (load.trace && m.rank == 0) std::fprintf(stderr, "    slow-mode extrapolation: factor %.2f\n", jump);
      if (modes_on) face_extrapolation.restart(m.face_mode_coordinates(face, basis));
      continue;  // the change measured before the jump says nothing about the new iterate
    }
    if (modes_on) {
      const auto c = face_extrapolation.after_iteration(m.face_mode_coordinates(face, basis));
      if (std::any_of(c.begin(), c.end(), [](double v) { return v != 0; })) {
        check(VecCopy(m.u, s.before_jump), "VecCopy");
        m.add_face_modes(basis, c);
        contact_before_jump = out.contact_nodes;
        extrapolation.restart(m.u);
        out.extrapolations = extrapolation.jumps() + face_extrapolation.jumps();
        if (load.trace && m.rank == 0)
          std::fprintf(stderr, "    face-mode extrapolation: slide (%.2e, %.2e) dilatation %.2e twist %.2e m\n", c[0],
                       c[1], c[2], c[3]);
        continue;
      }
    }
    if (final_pass && step_change > load.tolerance) {
      // Not confirmed: the loose solves were too loose to see the change that is left. Go on
      // loosely, ten times tighter.
      final_pass = false;
      loose_factor *= 0.1;
    }
    if (step_change <= load.tolerance && (rtol > load.ksp_rtol || !as.settled) && !final_pass) {
      final_pass = true;  // converged on loose solves: confirm with one full solve at ksp_rtol
      continue;
    }
    retrying = false;
    if (load.follow_geometry && step_change <= load.tolerance && load.max_penetration > 0) {
      // Small change, yet a node is inside the obstacle: the tolerance has not seen all that is
      // left (e.g. after a slow-mode jump, or while the capped damping averages a chatter out).
      // Go on, with ten times tighter loose solves, while the node keeps coming out.
      const double depth = m.deepest_penetration(face, damping.capped() ? m.u : s.ustar, load);
      retrying = depth > load.max_penetration;
      if (retrying && penetration_retries.retry(depth)) {
        if (load.trace && m.rank == 0)
          std::fprintf(stderr, "    penetration retry %d: deepest node %.2e m (limit %.2e m)\n",
                       penetration_retries.count(), depth, load.max_penetration);
        final_pass = false;
        loose_factor *= 0.1;
        continue;
      }
    }
    if (!load.follow_geometry || step_change <= load.tolerance) {
      // The undamped solution of the last linearisation; after a stagnation the averaged
      // iterate instead (u* still carries the chatter).
      if (!damping.capped()) check(VecCopy(s.ustar, m.u), "VecCopy");
      out.converged = true;
      if (newton && load.trace && curvature.all > 0) m.print_second_order_check(face, top, s, load, curvature);
      break;
    }
  }
  // The cap ended the retries: the change test was met, so the step ends as converged by it and
  // the penetration check (the caller's) names the node that is still too deep.
  if (!out.converged && retrying && out.message.empty()) {
    if (!damping.capped()) check(VecCopy(s.ustar, m.u), "VecCopy");
    out.converged = true;
  }
  if (!out.converged && out.message.empty())
    out.message = "Signorini iteration did not converge in " + std::to_string(load.max_outer_iterations) +
                  " iterations (last relative change " + (out.history.empty() ? "-" : std::to_string(out.history.back())) + ")";
  m.output_results(face, top, normal_force, load, s.r, out);
  return out;
}

}  // namespace wr
