#include "lib/fem/elastic_block_impl.hpp"

namespace wr {

using petsc::check;

std::array<double, 9> block_detail::frame_of(const Vec3& n) {
  std::array<double, 9> q{1, 0, 0, 0, 1, 0, 0, 0, 1};
  const Vec3 w{-n.x, -n.y, 1 - n.z};  // e_z - n
  const double ww = w.dot(w);
  if (ww < 1e-30) return q;
  const double wv[3] = {w.x, w.y, w.z};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q[r * 3 + c] -= 2 * wv[r] * wv[c] / ww;
  return q;
}

// ---- One solve(): Algorithm 1 of the thesis (sec. 4.2), one phase per function ----

std::vector<FaceNode> ElasticBlock::Impl::owned_face_nodes() const {
  const GradedMesh& g = *mesh;
  std::vector<FaceNode> face;
  for (int j = 0; j <= face_ny(); ++j)
    for (int i = g.owned_i_begin(rank, 0); i < g.owned_i_end(rank, 0); ++i) {
      const std::int32_t id = g.node(0, i, j);
      face.push_back(FaceNode{i, j, {dof(id, 0), dof(id, 1), dof(id, 2)}, g.position(0, i, j)});
    }
  return face;
}

ElasticBlock::Impl::TopBoundary ElasticBlock::Impl::prescribe_top(const ContactLoad& load) {
  const GradedMesh& g = *mesh;
  TopBoundary t;
  const int top = g.layers(), top_level = g.planes()[top].level;
  for (int j = 0; j <= g.cells_y(top_level); ++j)
    for (int i = g.owned_i_begin(rank, top_level); i < g.owned_i_end(rank, top_level); ++i)
      for (int c = 0; c < 3; ++c) {
        const PetscInt row = dof(g.node(top, i, j), c);
        t.top_rows[c].push_back(row);
        if (load.top == TopCondition::frictionless && c < 2) continue;
        t.fixed_rows.push_back(row);
        t.fixed_vals.push_back(c == 0 ? load.ux : (c == 1 ? 0.0 : -load.uz));
      }
  if (load.top == TopCondition::frictionless) {
    // In-plane rigid motion is free: pin two face corners.
    const std::int32_t c0 = g.node(0, 0, 0), c1 = g.node(0, face_nx(), 0);
    if (owns(c0)) {
      t.fixed_rows.insert(t.fixed_rows.end(), {dof(c0, 0), dof(c0, 1)});
      t.fixed_vals.insert(t.fixed_vals.end(), {0.0, 0.0});
    }
    if (owns(c1)) {
      t.fixed_rows.push_back(dof(c1, 1));
      t.fixed_vals.push_back(0.0);
    }
  }
  check(VecSetValues(u, PetscInt(t.fixed_rows.size()), t.fixed_rows.data(), t.fixed_vals.data(), INSERT_VALUES),
        "VecSetValues");
  check(VecAssemblyBegin(u), "VecAssemblyBegin");
  check(VecAssemblyEnd(u), "VecAssemblyEnd");
  return t;
}

ElasticBlock::Impl::LinearSystems::LinearSystems(MPI_Comm comm, Vec like, std::size_t face_nodes, AmgHierarchy amg,
                                                 LinearSolver solver, GeometricMultigrid* gmg)
    : q_all(9 * face_nodes), q_mine(q_all.size()) {
  for (Vec* v : {&uh, &b, &r, &diag, &ustar, &before_jump}) check(VecDuplicate(like, v), "VecDuplicate");
  check(KSPCreate(comm, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  if (solver == LinearSolver::gmg) {
    // The geometric multigrid (geometric_multigrid.hpp) on the matrix-free operator; its levels
    // take each reduced system's constraints in solve_active_set.
    gmg->attach(pc);
    check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
    return;
  }
  if (solver == LinearSolver::direct) {
    // Sparse Cholesky: CHOLMOD (SuiteSparse) where the matrix lives on one rank, MUMPS across
    // ranks. CG around it converges in one iteration, and the reuse policy of the active-set
    // loop keeps the factor as the preconditioner of the next, slightly different, system.
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    check(PCSetType(pc, PCCHOLESKY), "PCSetType");
    check(PCFactorSetMatSolverType(pc, ranks == 1 ? MATSOLVERCHOLMOD : MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
    return;
  }
  check(PCSetType(pc, PCGAMG), "PCSetType");
  // Chebyshev smoothers with eigenvalue bounds estimated by the smoothed-aggregation step came
  // out too low on rough-surface systems (KSP_DIVERGED_INDEFINITE_PC at tight tolerances):
  // estimate them per level, with a wider safety margin. Options given by the user win.
  set_default_option("-pc_gamg_use_sa_esteig", "0");
  set_default_option("-mg_levels_ksp_chebyshev_esteig", "0,0.1,0,1.2");
  // One smoothing step per level instead of PETSc's two: a V-cycle costs about half (the fine
  // level's matrix products dominate) for a few more CG iterations at most. 100 x 100 scene,
  // refine 2, tol 1e-3: 38 Signorini / 1227 CG iterations / 146 s in the solves against
  // 39 / 1409 / 305 s.
  set_default_option("-mg_levels_ksp_max_it", "1");
  if (amg == AmgHierarchy::lean) {
    // Unsmoothed aggregation: the prolongator keeps 6 entries per row and the coarse operators
    // stay sparse; set through the PC so that -pc_gamg_agg_nsmooths still overrides it.
    check(PCGAMGSetNSmooths(pc, 0), "PCGAMGSetNSmooths");
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    // All at once exists for parallel (MPIAIJ) products only; PETSc 3.18 refuses it on one rank.
    if (ranks > 1) ptap_option = std::make_unique<ScopedDefaultOption>("-matptap_via", "allatonce");
  }
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
}

ElasticBlock::Impl::LinearSystems::~LinearSystems() {
  KSPDestroy(&ksp);
  for (Vec* v : {&uh, &b, &r, &diag, &ustar, &before_jump, &shift}) VecDestroy(v);
}

void ElasticBlock::Impl::linearise(std::vector<FaceNode>& face, const ContactLoad& load) const {
  constexpr double kMinRayCosine = 0.5;  // of a ray with the downward vertical
  const GradedMesh& g = *mesh;
  const int fnx = face_nx(), fny = face_ny();
  const double reach = std::max(spec.mesh.lz, 1e-12);  // rays look this far for the obstacle
  gather_face();
  const PetscScalar* fu;
  check(VecGetArrayRead(face_u, &fu), "VecGetArrayRead");
  auto X = [&](int i, int j) {
    const std::size_t k = 3 * (std::size_t(j) * (fnx + 1) + i);
    return g.position(0, i, j) + Vec3{fu[k], fu[k + 1], fu[k + 2]};
  };
  if (load.smooth && load.follow_geometry) {
    // Newton: the contact condition g(x) = z - h(x, y) >= 0 linearised at the node's current
    // position p: grad g . (x - p) + g(p) >= 0, i.e. N . x >= N . q with N = grad g / |grad g|
    // and q = (p_x, p_y, h) the point of the obstacle below p. Exact to first order whatever
    // the slope, so no ray is needed.
    for (FaceNode& f : face) {
      const Vec3 p = X(f.i, f.j);
      const SmoothObstacle::Local o = load.smooth->at(p.x, p.y);
      f.normal = Vec3{-o.hx, -o.hy, 1.0}.unit();
      f.g = f.normal.dot(Vec3{p.x, p.y, o.h} - f.x0);
      f.hxx = o.hxx;
      f.hxy = o.hxy;
      f.hyy = o.hyy;
    }
    VecRestoreArrayRead(face_u, &fu);
    return;
  }
  for (FaceNode& f : face) {
    if (!load.obstacle) {
      f.normal = {0, 0, 1};
      f.g = 0.0;
      continue;
    }
    if (!load.follow_geometry) {
      f.normal = {0, 0, 1};
      f.g = load.obstacle->height(f.x0.x, f.x0.y);
      continue;
    }
    const Vec3 here = X(f.i, f.j);
    // Outward normal of the deformed face (pointing down), from the neighbours' positions.
    const Vec3 t1 = X(std::min(f.i + 1, fnx), f.j) - X(std::max(f.i - 1, 0), f.j);
    const Vec3 t2 = X(f.i, std::min(f.j + 1, fny)) - X(f.i, std::max(f.j - 1, 0));
    Vec3 n = t2.cross(t1).unit();
    // Which side of the obstacle a node is on decides which crossing is its gap
    // (PeriodicObstacle::cast), so the ray must point down. On steep obstacles the face's
    // edge nodes, pressed into flanks, can fold their elements over (on a 100 x 100 patch of
    // slope 1.8 at 30 % compression: face normals up to 80 degrees from vertical, some
    // pointing up); there the vertical stands in.
    if (n.z > -kMinRayCosine) n = {0, 0, -1};
    // A node inside the obstacle is held to the tangent plane where its ray's line comes out.
    // Along a tilted ray that plane can leave the node inside it (the ray glancing a flank
    // whose normal is more than 90 degrees from -n): a fixed point of Algorithm 1 with the
    // node still in. Along the vertical the plane always cuts the node off, and the step
    // it asks for, (h - z) n_z, is the penetration face_gaps measures.
    if (here.z < load.obstacle->height(here.x, here.y)) n = {0, 0, -1};
    const auto hit = load.obstacle->cast(here, n, reach);
    if (!hit) {
      f.normal = {0, 0, 1};
      f.g = -INFINITY;
      continue;
    }
    if (load.block_normals > 0) {
      // The virtual plane of sec. 4.2.1: through the hit, orthogonal to the block's normal
      // (flipped to point out of the obstacle, as N does). Relaxed from the last one used;
      // a node's first linearisation of the step (no bound yet) takes n_k itself.
      const Vec3 nk = n * -1.0;
      f.normal = std::isfinite(f.g) ? (f.normal + (nk - f.normal) * load.block_normals).unit() : nk;
    } else {
      f.normal = !load.facet_normals      ? hit->normal
                 : load.facet_band > 0 ? load.obstacle->banded_facet_normal(hit->point, load.facet_band)
                                       : load.obstacle->normal(hit->point.x, hit->point.y);
    }
    f.g = f.normal.dot(hit->point - f.x0);  // N . (x0 + u) >= N . q, N the constraint normal
  }
  VecRestoreArrayRead(face_u, &fu);
}

ElasticBlock::Impl::SurfacePoint ElasticBlock::Impl::surface_at(const ContactLoad& load, double x, double y) {
  SurfacePoint p;
  if (load.smooth) {
    const SmoothObstacle::Local o = load.smooth->at(x, y);
    p.h = o.h;
    p.nz = 1.0 / std::sqrt(1.0 + o.hx * o.hx + o.hy * o.hy);
  } else if (load.obstacle) {
    p.h = load.obstacle->height(x, y);
    p.nz = load.obstacle->normal(x, y).z;
  }
  return p;
}

namespace {

// A face node's curvature block, global frame, row-major: lambda [[hxx, hxy, 0], [hxy, hyy, 0],
// [0, 0, 0]], the Hessian of -lambda g for g = z - h(x, y), split by the sign of its
// eigenvalues. Where the obstacle curves up (a valley) the term stiffens the node's sliding and
// is kept whole; where it curves down (an asperity's top) it softens it, and a system whose
// multipliers are still poor estimates (early iterations) can then be indefinite: that part is
// scaled by `negative` (in [0, 1], cut by the caller after an indefinite system) and bounded
// below by -kBound x the node's own stiffness `k`. Returns whether the bound acted.
bool curvature_block(const FaceNode& f, double lambda, double negative, double k, double* c) {
  constexpr double kBound = 0.5;
  const double a = lambda * f.hxx, b = lambda * f.hxy, d = lambda * f.hyy;
  const double m = 0.5 * (a + d), r = std::hypot(0.5 * (a - d), b);
  const double phi = 0.5 * std::atan2(2 * b, a - d);  // direction of the larger eigenvalue
  double hi = m + r, lo = m - r;
  auto soften = [&](double e) { return e >= 0 ? e : std::max(negative * e, -kBound * k); };
  const bool clipped = negative * std::min(lo, 0.0) < -kBound * k;
  hi = soften(hi);
  lo = soften(lo);
  const double cs = std::cos(phi), sn = std::sin(phi);
  const double block[9] = {hi * cs * cs + lo * sn * sn, (hi - lo) * cs * sn, 0,
                           (hi - lo) * cs * sn, hi * sn * sn + lo * cs * cs, 0, 0, 0, 0};
  std::copy(block, block + 9, c);
  return clipped;
}

}  // namespace

double ElasticBlock::Impl::rotate_into_frames(const std::vector<FaceNode>& face, LinearSystems& s,
                                              const CurvatureScales& curvature, int& clipped) {
  const int fnx = face_nx();
  clipped = 0;
  std::fill(s.q_mine.begin(), s.q_mine.end(), 0.0);
  for (const FaceNode& f : face) {
    const auto q = frame_of(f.normal);
    std::copy(q.begin(), q.end(), s.q_mine.begin() + 9 * (std::size_t(f.j) * (fnx + 1) + std::size_t(f.i)));
  }
  MPI_Allreduce(s.q_mine.data(), s.q_all.data(), int(s.q_all.size()), MPI_DOUBLE, MPI_SUM, comm);
  stiffness->set_frames(s.q_all);
  if (curvature.on) {
    const double scale_all = curvature.all, negative = curvature.negative;
    const PetscInt rstart = 3 * PetscInt(own_begin);
    if (face_stiffness.empty()) {
      // Before any block is added the diagonal blocks are K's, rotated: their trace is K's.
      check(MatGetDiagonal(stiffness->mat(), s.diag), "MatGetDiagonal");
      const PetscScalar* da;
      VecGetArrayRead(s.diag, &da);
      for (const FaceNode& f : face)
        face_stiffness.push_back((da[f.row[0] - rstart] + da[f.row[1] - rstart] + da[f.row[2] - rstart]) / 3);
      VecRestoreArrayRead(s.diag, &da);
    }
    // C per face slot (the q_mine buffer, zeroed: only the owned slots are read), and C u.
    std::fill(s.q_mine.begin(), s.q_mine.end(), 0.0);
    if (!s.shift) check(VecDuplicate(u, &s.shift), "VecDuplicate");
    check(VecSet(s.shift, 0.0), "VecSet");
    const PetscScalar* ua;
    PetscScalar* sa;
    VecGetArrayRead(u, &ua);
    VecGetArray(s.shift, &sa);
    for (std::size_t n = 0; n < face.size(); ++n) {
      const FaceNode& f = face[n];
      if (lambda[n] == 0 || scale_all == 0) continue;
      double* c = &s.q_mine[9 * (std::size_t(f.j) * (fnx + 1) + std::size_t(f.i))];
      clipped += curvature_block(f, scale_all * lambda[n], negative, face_stiffness[n], c);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) sa[f.row[i] - rstart] += c[3 * i + j] * ua[f.row[j] - rstart];
    }
    VecRestoreArrayRead(u, &ua);
    VecRestoreArray(s.shift, &sa);
    stiffness->set_face_blocks(s.q_mine);
    stiffness->rotate_vector(s.shift, s.q_all, true);
  }
  check(MatGetDiagonal(stiffness->mat(), s.diag), "MatGetDiagonal");
  check(VecCopy(u, s.uh), "VecCopy");
  stiffness->rotate_vector(s.uh, s.q_all, true);
  // Eliminated rows get a diagonal of the matrix's own scale, so that AMG smoothers see no
  // stray unit entries among stiffnesses of order E h.
  PetscScalar diag_sum;
  PetscInt diag_n;
  VecSum(s.diag, &diag_sum);
  VecGetSize(s.diag, &diag_n);
  return diag_sum / double(diag_n);
}

void ElasticBlock::Impl::print_second_order_check(std::vector<FaceNode>& face, const TopBoundary& top,
                                                  LinearSystems& s, const ContactLoad& load, CurvatureScales full) {
  // What the step's result still needs from the systems: the reactions and the contact set.
  Vec r_kept = nullptr;
  check(VecDuplicate(s.r, &r_kept), "VecDuplicate");
  check(VecCopy(s.r, r_kept), "VecCopy");
  const std::vector<char> active_kept = active;
  linearise(face, load);
  double slide[2] = {0, 0};
  for (std::size_t n = 0; n < face.size(); ++n) {
    slide[0] += lambda[n] * face[n].hxx;
    slide[1] += lambda[n] * face[n].hyy;
  }
  double slide_all[2];
  MPI_Allreduce(slide, slide_all, 2, MPI_DOUBLE, MPI_SUM, comm);
  full.negative = 1;
  int clipped = 0, clipped_all = 0;
  ActiveSetControl control;
  control.unit_diag = rotate_into_frames(face, s, full, clipped);
  MPI_Allreduce(&clipped, &clipped_all, 1, MPI_INT, MPI_SUM, comm);
  control.max_iterations = load.max_active_set_iterations;
  // Tight: CG meets a direction of negative curvature only once its Krylov space holds one.
  check(KSPSetTolerances(s.ksp, std::min(load.ksp_rtol, 1e-10), 1e-300, PETSC_DEFAULT, 20000), "KSPSetTolerances");
  ContactSolution probe;
  probe.face_nodes = std::size_t(face_nx() + 1) * (face_ny() + 1);
  const ActiveSetOutcome as = solve_active_set(face, top, s, control, probe);
  const double shear = spec.young / (2 * (1 + spec.poisson)) * spec.mesh.lx * spec.mesh.ly / spec.mesh.lz;
  if (rank == 0)
    std::fprintf(stderr,
                 "    second-order check: the whole curvature term (%d nodes at the floor) gives %s system "
                 "(%d CG iterations)%s; rigid slide: sum lambda h_xx %.3e, h_yy %.3e N/m against the block's shear "
                 "stiffness %.3e N/m\n",
                 clipped_all, as.ok ? "a definite" : "an INDEFINITE", probe.linear_iterations,
                 as.ok ? "" : ": negative curvature on the contact set's tangent space, the state held only by nodes at zero gap and force (degenerate: no quadratic rate)",
                 slide_all[0], slide_all[1], shear);
  active = active_kept;
  check(VecCopy(r_kept, s.r), "VecCopy");
  VecDestroy(&r_kept);
}

}  // namespace wr
