#include "lib/fem/elastic_block_impl.hpp"

namespace wr {

using petsc::check;

ElasticBlock::Impl::ActiveSetOutcome ElasticBlock::Impl::solve_active_set(const std::vector<FaceNode>& face,
                                                                          const TopBoundary& top, LinearSystems& s,
                                                                          const ActiveSetControl& control,
                                                                          ContactSolution& out) {
  const PetscInt rstart = 3 * PetscInt(own_begin);
  ActiveSetOutcome res;
  {
    const PetscScalar* a;
    VecGetArrayRead(s.uh, &a);
    for (std::size_t n = 0; n < face.size(); ++n)
      if (std::isfinite(face[n].g) && a[face[n].row[2] - rstart] <= face[n].g) active[n] = 1;
      else if (!std::isfinite(face[n].g)) active[n] = 0;
    VecRestoreArrayRead(s.uh, &a);
  }
  for (int it = 0; it < control.max_iterations; ++it) {
    ++out.active_set_iterations;
    std::vector<PetscInt> rows = top.fixed_rows;
    std::vector<double> vals = top.fixed_vals;
    for (std::size_t n = 0; n < face.size(); ++n)
      if (active[n]) {
        rows.push_back(face[n].row[2]);
        vals.push_back(face[n].g);
      }
    check(VecSetValues(s.uh, PetscInt(rows.size()), rows.data(), vals.data(), INSERT_VALUES), "VecSetValues");
    check(VecAssemblyBegin(s.uh), "VecAssemblyBegin");
    check(VecAssemblyEnd(s.uh), "VecAssemblyEnd");
    stiffness->eliminate(rows, control.unit_diag, s.uh, s.b, s.shift);
    if (gmg) gmg->update();
    check(KSPSetOperators(s.ksp, stiffness->mat(), stiffness->mat()), "KSPSetOperators");
    PetscBool reused = PETSC_FALSE;
    KSPGetReusePreconditioner(s.ksp, &reused);
    if (reused) check(VecCopy(s.uh, s.ustar), "VecCopy");  // the start, in case the solve must be redone
    check(KSPSolve(s.ksp, s.b, s.uh), "KSPSolve");
    KSPConvergedReason reason;
    PetscInt its;
    KSPGetConvergedReason(s.ksp, &reason);
    KSPGetIterationNumber(s.ksp, &its);
    out.linear_iterations += int(its);
    if (reason < 0 && reused) {
      // A hierarchy kept from an earlier system can stop being a good (or even positive
      // definite, with its Chebyshev bounds) preconditioner for this one: rebuild and redo.
      check(KSPSetReusePreconditioner(s.ksp, PETSC_FALSE), "KSPSetReusePreconditioner");
      check(VecCopy(s.ustar, s.uh), "VecCopy");
      check(KSPSolve(s.ksp, s.b, s.uh), "KSPSolve");
      KSPGetConvergedReason(s.ksp, &reason);
      KSPGetIterationNumber(s.ksp, &its);
      out.linear_iterations += int(its);
      s.first_its = int(its);
      ++out.preconditioner_rebuilds;
    }
    stiffness->restore();
    if (control.loose && it == 0) set_convergence_test(s.ksp, 0.0);
    // Keep the AMG hierarchy of the first system for the later ones of this load step (the
    // systems differ only by rotations and eliminated rows); rebuild it when CG slows down.
    if (control.reuse_preconditioner) {
      if (s.first_its < 0) s.first_its = int(its);
      const bool slow = s.first_its >= 0 && its > 3 * std::max(s.first_its, 10);
      check(KSPSetReusePreconditioner(s.ksp, slow ? PETSC_FALSE : PETSC_TRUE), "KSPSetReusePreconditioner");
      if (slow) s.first_its = -1;
    }
    if (reason < 0) {
      out.message = "linear solve failed (KSP reason " + std::to_string(int(reason)) + ") in Signorini iteration " +
                    std::to_string(out.outer_iterations);
      return res;
    }
    check(MatMult(stiffness->mat(), s.uh, s.r), "MatMult");  // reactions in the rotated frames
    if (s.shift) check(VecAXPY(s.r, -1.0, s.shift), "VecAXPY");  // Newton: K u* + C (u* - u)
    const PetscScalar *ra, *ua, *da;
    VecGetArrayRead(s.r, &ra);
    VecGetArrayRead(s.uh, &ua);
    VecGetArrayRead(s.diag, &da);
    int changed = 0;
    res.contact = 0;
    for (std::size_t n = 0; n < face.size(); ++n) {
      if (!std::isfinite(face[n].g)) continue;
      const PetscInt l = face[n].row[2] - rstart;
      const bool now = ra[l] + da[l] * (face[n].g - ua[l]) > 0;
      changed |= now != bool(active[n]);
      active[n] = now;
      res.contact += now;
    }
    VecRestoreArrayRead(s.r, &ra);
    VecRestoreArrayRead(s.uh, &ua);
    VecRestoreArrayRead(s.diag, &da);
    int any = 0;
    MPI_Allreduce(&changed, &any, 1, MPI_INT, MPI_MAX, comm);
    if (!any) {
      res.ok = res.settled = true;
      return res;
    }
    if (control.accept_unsettled && it + 1 == control.max_iterations) res.ok = true;  // the next Signorini iteration goes on
  }
  return res;
}

ElasticBlock::Impl::Correction ElasticBlock::Impl::measure_correction(const std::vector<FaceNode>& face, Vec ustar,
                                                                      std::vector<double>& prev_corr) const {
  const PetscInt rstart = 3 * PetscInt(own_begin);
  const PetscScalar *us, *uc;
  VecGetArrayRead(ustar, &us);
  VecGetArrayRead(u, &uc);
  // {|c|^2, c.c_prev, |c_prev|^2, |u*|^2} over the face, c = u* - u.
  double sums[4] = {0, 0, 0, 0}, g[4];
  for (std::size_t n = 0; n < face.size(); ++n)
    for (int c = 0; c < 3; ++c) {
      const PetscInt l = face[n].row[c] - rstart;
      const double corr = us[l] - uc[l];
      sums[0] += corr * corr;
      sums[1] += corr * prev_corr[3 * n + c];
      sums[2] += prev_corr[3 * n + c] * prev_corr[3 * n + c];
      sums[3] += us[l] * us[l];
      prev_corr[3 * n + c] = corr;
    }
  VecRestoreArrayRead(ustar, &us);
  VecRestoreArrayRead(u, &uc);
  MPI_Allreduce(sums, g, 4, MPI_DOUBLE, MPI_SUM, comm);
  Correction c;
  c.change = g[3] > 0 ? std::sqrt(g[0] / g[3]) : 0.0;
  c.cosine = g[2] > 0 ? g[1] / std::sqrt(g[0] * g[2]) : NAN;
  return c;
}

ElasticBlock::Impl::FaceGaps ElasticBlock::Impl::face_gaps(const std::vector<FaceNode>& face, const PetscScalar* a,
                                                           const ContactLoad& load) const {
  const PetscInt rstart = 3 * PetscInt(own_begin);
  FaceGaps out;
  for (const FaceNode& f : face) {
    const Vec3 p{f.x0.x + a[f.row[0] - rstart], f.x0.y + a[f.row[1] - rstart], a[f.row[2] - rstart]};
    const SurfacePoint sp = surface_at(load, p.x, p.y);
    out.separation += std::max(0.0, p.z - sp.h);
    if (sp.h <= p.z) continue;
    // Penetration as a distance: perpendicular to the surface above the node. The vertical
    // depth overstates it by sqrt(1 + slope^2), 2.2x on the slope-2 flanks where the last nodes
    // of the thesis's Problem A sit, and the linearised constraint bounds the normal gap.
    const double depth = (sp.h - p.z) * sp.nz;
    if (depth > out.deepest) {
      out.deepest = depth;
      out.deepest_at = p;
    }
    if (load.max_penetration > 0 && depth > load.max_penetration) ++out.over_limit;
  }
  return out;
}

double ElasticBlock::Impl::deepest_penetration(const std::vector<FaceNode>& face, Vec v, const ContactLoad& load) const {
  const PetscScalar* a;
  VecGetArrayRead(v, &a);
  const double pen = face_gaps(face, a, load).deepest;
  VecRestoreArrayRead(v, &a);
  double pen_g = 0;
  MPI_Allreduce(&pen, &pen_g, 1, MPI_DOUBLE, MPI_MAX, comm);
  return pen_g;
}

std::array<double, 3> ElasticBlock::Impl::top_forces(Vec v, const TopBoundary& top, Vec work) const {
  const PetscInt rstart = 3 * PetscInt(own_begin);
  stiffness->multiply_unrotated(v, work);
  const PetscScalar* ra;
  VecGetArrayRead(work, &ra);
  double f[3] = {0, 0, 0};
  std::array<double, 3> fg;
  for (PetscInt row : top.top_rows[0]) f[0] += ra[row - rstart];
  for (PetscInt row : top.top_rows[1]) f[1] += ra[row - rstart];
  for (PetscInt row : top.top_rows[2]) f[2] -= ra[row - rstart];
  VecRestoreArrayRead(work, &ra);
  MPI_Allreduce(f, fg.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  return fg;
}

void ElasticBlock::Impl::output_results(const std::vector<FaceNode>& face, const TopBoundary& top,
                                        const std::vector<double>& normal_force, const ContactLoad& load, Vec work,
                                        ContactSolution& out) const {
  const GradedMesh& g = *mesh;
  const int fnx = face_nx(), fny = face_ny();
  const PetscInt rstart = 3 * PetscInt(own_begin);
  const auto forces = top_forces(u, top, work);
  out.fx = forces[0];
  out.fy = forces[1];
  out.fz = forces[2];
  const PetscScalar* uu;
  VecGetArrayRead(u, &uu);
  const FaceGaps gaps = face_gaps(face, uu, load);
  if (load.face_maps) {
    const std::size_t nfx = std::size_t(fnx + 1), nf = nfx * std::size_t(fny + 1);
    std::vector<double> local(3 * nf, 0.0);
    for (std::size_t n = 0; n < face.size(); ++n) {
      const FaceNode& f = face[n];
      const std::size_t idx = std::size_t(f.j) * nfx + std::size_t(f.i);
      // Nodal area: a quarter cell per adjacent cell.
      const double wx = (f.i == 0 || f.i == fnx) ? 0.5 : 1.0, wy = (f.j == 0 || f.j == fny) ? 0.5 : 1.0;
      local[idx] = normal_force[n] / (wx * wy * g.hx(0) * g.hy(0));
      const Vec3 p{f.x0.x + uu[f.row[0] - rstart], f.x0.y + uu[f.row[1] - rstart], uu[f.row[2] - rstart]};
      local[nf + idx] = p.z - surface_at(load, p.x, p.y).h;
      local[2 * nf + idx] = active[n] ? 1.0 : 0.0;
    }
    std::vector<double> global(3 * nf, 0.0);
    MPI_Reduce(local.data(), global.data(), int(3 * nf), MPI_DOUBLE, MPI_SUM, 0, comm);
    out.face_pressure.assign(global.begin(), global.begin() + nf);
    out.face_gap.assign(global.begin() + nf, global.begin() + 2 * nf);
    out.face_status.assign(global.begin() + 2 * nf, global.end());
  }
  VecRestoreArrayRead(u, &uu);
  double sums[2] = {gaps.separation, double(gaps.over_limit)}, sums_g[2];
  MPI_Allreduce(sums, sums_g, 2, MPI_DOUBLE, MPI_SUM, comm);
  out.mean_separation = sums_g[0] / double(out.face_nodes);
  out.nodes_over_penetration = std::size_t(sums_g[1]);
  // The deepest node and where it is: every rank's candidate, the deepest kept.
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const double mine[4] = {gaps.deepest, gaps.deepest_at.x, gaps.deepest_at.y, gaps.deepest_at.z};
  std::vector<double> all(4 * std::size_t(ranks));
  MPI_Allgather(mine, 4, MPI_DOUBLE, all.data(), 4, MPI_DOUBLE, comm);
  std::size_t best = 0;  // offset of the deepest rank's record in `all`
  for (std::size_t r = 4; r < all.size(); r += 4)
    if (all[r] > all[best]) best = r;
  out.max_penetration = all[best];
  out.deepest_at = {all[best + 1], all[best + 2], all[best + 3]};
}

FaceModeExtrapolation::Modes ElasticBlock::Impl::face_mode_coordinates(const std::vector<FaceNode>& face,
                                                                       const FaceModeBasis& basis) const {
  constexpr int kModes = FaceModeExtrapolation::kModes;
  const PetscInt rstart = 3 * PetscInt(own_begin);
  const PetscScalar* a;
  VecGetArrayRead(u, &a);
  double s[2 * kModes] = {}, sg[2 * kModes];
  for (const FaceNode& f : face)
    for (int k = 0; k < kModes; ++k) {
      const auto phi = basis.shape(f.x0.x, f.x0.y, k);
      s[k] += phi[0] * a[f.row[0] - rstart] + phi[1] * a[f.row[1] - rstart];
      s[kModes + k] += phi[0] * phi[0] + phi[1] * phi[1];
    }
  VecRestoreArrayRead(u, &a);
  MPI_Allreduce(s, sg, 2 * kModes, MPI_DOUBLE, MPI_SUM, comm);
  FaceModeExtrapolation::Modes c;
  for (int k = 0; k < kModes; ++k) c[k] = sg[k] / sg[kModes + k];
  return c;
}

void ElasticBlock::Impl::add_face_modes(const FaceModeBasis& basis, const FaceModeExtrapolation::Modes& c) {
  for_each_lifted_node([&](const Vec3& x, double w, PetscScalar* d) {
    for (int k = 0; k < FaceModeExtrapolation::kModes; ++k) {
      const auto phi = basis.shape(x.x, x.y, k);
      d[0] += w * c[k] * phi[0];
      d[1] += w * c[k] * phi[1];
    }
  });
}

}  // namespace wr
