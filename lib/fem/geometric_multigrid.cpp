#include "lib/fem/geometric_multigrid.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "lib/fem/elastic_block_impl.hpp"
#include "lib/fem/framed_stiffness.hpp"

namespace wr {

using petsc::check;

GmgSettings gmg_settings_from_options() {
  GmgSettings s;
  PetscBool set = PETSC_FALSE;
  PetscInt v = 0;
  if (PetscOptionsGetInt(nullptr, nullptr, "-gmg_degree", &v, &set) == 0 && set) s.degree = std::max<PetscInt>(1, v);
  if (PetscOptionsGetInt(nullptr, nullptr, "-gmg_max_levels", &v, &set) == 0 && set) s.max_levels = std::max<PetscInt>(2, v);
  if (PetscOptionsGetInt(nullptr, nullptr, "-gmg_esteig_steps", &v, &set) == 0 && set)
    s.estimate_steps = std::max<PetscInt>(2, v);
  PetscReal r = 0;
  if (PetscOptionsGetReal(nullptr, nullptr, "-gmg_coarse_nodes", &r, &set) == 0 && set) s.coarse_nodes = r;
  if (PetscOptionsGetReal(nullptr, nullptr, "-gmg_direct_nodes", &r, &set) == 0 && set) s.direct_nodes = r;
  PetscBool flag = PETSC_FALSE;
  if (PetscOptionsGetBool(nullptr, nullptr, "-gmg_coarse_constraints", &flag, &set) == 0 && set)
    s.coarse_constraints = flag == PETSC_TRUE;
  if (PetscOptionsGetBool(nullptr, nullptr, "-gmg_single", &flag, &set) == 0 && set) s.single = flag == PETSC_TRUE;
  PetscReal pair[2];
  PetscInt n = 2;
  if (PetscOptionsGetRealArray(nullptr, nullptr, "-gmg_esteig", pair, &n, &set) == 0 && set && n == 2 && pair[0] > 0 &&
      pair[1] > pair[0]) {
    s.esteig_lo = pair[0];
    s.esteig_hi = pair[1];
  }
  return s;
}

struct GeometricMultigrid::Level {
  std::unique_ptr<GradedMesh> own_mesh;
  const GradedMesh* mesh = nullptr;
  std::int32_t own_begin = 0, own_end = 0;
  std::vector<std::int32_t> face_slot;
  std::unique_ptr<MatrixFreeFramed> own_mf;
  MatrixFreeFramed* mf = nullptr;              // the smoothed levels' operator
  std::unique_ptr<FramedStiffness> assembled;  // the coarsest level's, in its frames
  Mat pristine = nullptr;                      // the coarsest level's K in the global frame
  KSP coarse = nullptr;
  Mat scalar_interp = nullptr, interp = nullptr;  // from the next coarser level to this one (MAIJ)
  Vec b = nullptr, x = nullptr, r = nullptr, p = nullptr, t = nullptr, dinv = nullptr;
  std::vector<double> frames;                   // the coarsest level's (the others': mf->frames())
  std::vector<PetscInt> eliminated;             // the coarsest level's (the others': mf->eliminated())
  std::vector<double> factored_frames;          // what the coarsest factor was made with
  std::vector<PetscInt> factored_rows;
  std::vector<unsigned char> face_mask, top_mask;  // eliminated components (bits), all face / top nodes
  double unit_diag = 1;
  double lambda = 0;                      // estimated largest eigenvalue of D^-1 A
  double seconds = 0;                     // in this level's smoothing, residual and transfers (or coarse solve)
  long products = 0;                      // operator products on this level
  unsigned long frames_seen = ~0ul;       // level 0: mf->frames_version() at the last estimate
  std::size_t interp_bytes = 0;

  int nx() const { return mesh->cells_x(0); }
  int ny() const { return mesh->cells_y(0); }
  int top_plane() const { return mesh->layers(); }
  int top_nx() const { return mesh->cells_x(mesh->planes().back().level); }
  int top_ny() const { return mesh->cells_y(mesh->planes().back().level); }
  const std::vector<double>& current_frames() const { return mf ? mf->frames() : frames; }
  const std::vector<PetscInt>& current_eliminated() const { return mf ? mf->eliminated() : eliminated; }
};

namespace {

std::vector<std::int32_t> face_slots_of(const GradedMesh& g) {
  std::vector<std::int32_t> slot(std::size_t(g.nodes()), -1);
  const int nx = g.cells_x(0), ny = g.cells_y(0);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) slot[std::size_t(g.node(0, i, j))] = j * (nx + 1) + i;
  return slot;
}

// The next level's face cells: about half, rounded to a multiple of 8 (of 2 below 16), so that
// the level's own mesh keeps coarsening in depth. Why: an odd count stops a GradedMesh's in-plane
// doublings, and the thesis scene's 300 cells halved to 150 would coarsen once, to 75, and be a
// 75 x 75 plate all the way up: a level 44 % the size of the fine one instead of about a quarter.
int half_even(int n) {
  const int half = n / 2, step = half >= 16 ? 8 : 2;
  return std::max(step, int(std::lround(double(half) / step)) * step);
}

// The index of the fine lattice point (n_f cells over the same length) nearest to coarse point i.
int nearest(int i, int n_coarse, int n_fine) {
  return std::clamp(int(std::lround(double(i) * n_fine / n_coarse)), 0, n_fine);
}

// A value in [-1, 1] per global dof, the same for any rank count (the eigenvalue estimate's start).
double start_value(PetscInt dof) {
  std::uint64_t z = std::uint64_t(dof) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) / double(1ull << 52) - 1.0;
}

// The scalar trilinear interpolation from mesh `coarse` to the owned nodes of mesh `fine`
// (rows: fine nodes, columns: coarse nodes), both partitioned over `comm`.
Mat interpolation(const GradedMesh& fine, const GradedMesh& coarse, MPI_Comm comm, int rank) {
  const std::int32_t fb = fine.owned_begin(rank), fe = fine.owned_end(rank);
  const std::int32_t cb = coarse.owned_begin(rank), ce = coarse.owned_end(rank);
  std::vector<std::vector<GradedMesh::Parent>> rows(std::size_t(fe - fb));
  std::vector<GradedMesh::Parent> w;
  const auto& planes = fine.planes();
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const int nxp = fine.cells_x(planes[p].level), nyp = fine.cells_y(planes[p].level);
    for (int j = 0; j <= nyp; ++j)
      for (int i = 0; i <= nxp; ++i) {
        const std::int32_t id = planes[p].id[std::size_t(j) * (nxp + 1) + i];
        if (id < fb || id >= fe) continue;
        coarse.interpolation_at(fine.position(int(p), i, j), w);
        rows[std::size_t(id - fb)] = w;
      }
  }
  std::vector<PetscInt> d_nnz(rows.size()), o_nnz(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (const auto& q : rows[r]) ++(q.id >= cb && q.id < ce ? d_nnz[r] : o_nnz[r]);
  Mat S = nullptr;
  check(MatCreateAIJ(comm, fe - fb, ce - cb, PETSC_DETERMINE, PETSC_DETERMINE, 0, d_nnz.data(), 0, o_nnz.data(), &S),
        "MatCreateAIJ");
  std::vector<PetscInt> cols;
  std::vector<double> vals;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    cols.clear();
    vals.clear();
    for (const auto& q : rows[r]) {
      cols.push_back(q.id);
      vals.push_back(q.weight);
    }
    const PetscInt row = fb + PetscInt(r);
    check(MatSetValues(S, 1, &row, PetscInt(cols.size()), cols.data(), vals.data(), INSERT_VALUES), "MatSetValues");
  }
  check(MatAssemblyBegin(S, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(S, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return S;
}

void zero_rows(Vec v, const std::vector<PetscInt>& rows, PetscInt first) {
  if (rows.empty()) return;
  PetscScalar* a;
  check(VecGetArray(v, &a), "VecGetArray");
  for (PetscInt r : rows) a[r - first] = 0;
  check(VecRestoreArray(v, &a), "VecRestoreArray");
}

double mean_entry(Vec v) {
  PetscScalar sum = 0;
  PetscInt n = 0;
  VecSum(v, &sum);
  VecGetSize(v, &n);
  return n > 0 ? double(sum) / double(n) : 1.0;
}

}  // namespace

GeometricMultigrid::GeometricMultigrid(const GradedMeshSpec& spec, const GradedMesh& fine_mesh, MatrixFreeFramed& fine,
                                       MPI_Comm comm, double young, double poisson, const GmgSettings& settings)
    : comm_(comm), set_(settings) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  auto level0 = std::make_unique<Level>();
  level0->mesh = &fine_mesh;
  level0->mf = &fine;
  level0->face_slot = fine.face_slot();
  levels_.push_back(std::move(level0));
  // The coarser meshes: the face spacing doubled while the counts stay even, down to coarse_nodes.
  GradedMeshSpec s = spec;
  while (int(levels_.size()) < set_.max_levels) {
    const Level& prev = *levels_.back();
    if (levels_.size() > 1 && double(prev.mesh->nodes()) <= set_.coarse_nodes) break;
    if (s.nx < 4 || s.ny < 4) break;
    GradedMeshSpec next = s;
    next.nx = half_even(s.nx);
    next.ny = half_even(s.ny);
    std::unique_ptr<GradedMesh> m;
    try {
      m = std::make_unique<GradedMesh>(next, ranks);
    } catch (const std::invalid_argument&) {
      break;
    }
    s = next;
    auto L = std::make_unique<Level>();
    L->own_mesh = std::move(m);
    L->mesh = L->own_mesh.get();
    L->face_slot = face_slots_of(*L->mesh);
    levels_.push_back(std::move(L));
  }
  if (levels_.size() < 2)
    throw std::runtime_error("geometric multigrid: the block's face cannot be coarsened (its cell counts must be even)");
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    Level& L = *levels_[k];
    L.own_begin = L.mesh->owned_begin(rank);
    L.own_end = L.mesh->owned_end(rank);
    const bool coarsest = k + 1 == levels_.size();
    if (k > 0 && !coarsest) {
      L.own_mf = std::make_unique<MatrixFreeFramed>(*L.mesh, comm, young, poisson, L.face_slot);
      L.mf = L.own_mf.get();
    }
    if (coarsest) {
      L.pristine = block_detail::assemble_stiffness(*L.mesh, comm, young, poisson);
      Mat copy = nullptr;
      check(MatDuplicate(L.pristine, MAT_COPY_VALUES, &copy), "MatDuplicate");
      L.assembled = std::make_unique<FramedStiffness>(copy, L.own_begin, L.own_end, L.face_slot);
      L.frames = L.assembled->frames();
      check(KSPCreate(comm, &L.coarse), "KSPCreate");
      check(KSPSetType(L.coarse, KSPPREONLY), "KSPSetType");
      PC pc;
      check(KSPGetPC(L.coarse, &pc), "KSPGetPC");
      if (double(L.mesh->nodes()) <= set_.direct_nodes) {
        check(PCSetType(pc, PCCHOLESKY), "PCSetType");
        check(PCFactorSetMatSolverType(pc, ranks == 1 ? MATSOLVERCHOLMOD : MATSOLVERMUMPS), "PCFactorSetMatSolverType");
      } else {
        // A plate of 76 x 76 cells or more: its factor's dense separators cost minutes, so the
        // coarsest level gets one AMG V-cycle instead (a fixed, symmetric operator: CG may use it).
        check(PCSetType(pc, PCGAMG), "PCSetType");
        coarse_amg_ = true;
      }
      check(KSPSetOptionsPrefix(L.coarse, "gmg_coarse_"), "KSPSetOptionsPrefix");
      check(KSPSetFromOptions(L.coarse), "KSPSetFromOptions");
    }
    const PetscInt n = 3 * PetscInt(L.own_end - L.own_begin);
    check(VecCreateMPI(comm, n, PETSC_DETERMINE, &L.b), "VecCreateMPI");
    for (Vec* v : {&L.x, &L.r, &L.p, &L.t, &L.dinv}) check(VecDuplicate(L.b, v), "VecDuplicate");
    // Eliminated rows get the level's mean diagonal (any positive value would do: their residual
    // is zeroed by the transfers; this one keeps D^-1 A's spectrum unstretched).
    if (L.mf) {
      L.mf->diagonal(L.dinv);
      L.unit_diag = mean_entry(L.dinv);
    } else {
      check(MatGetDiagonal(L.assembled->mat(), L.dinv), "MatGetDiagonal");
      L.unit_diag = mean_entry(L.dinv);
    }
    L.face_mask.assign(std::size_t(L.nx() + 1) * (L.ny() + 1), 0);
    L.top_mask.assign(std::size_t(L.top_nx() + 1) * (L.top_ny() + 1), 0);
  }
  for (std::size_t k = 0; k + 1 < levels_.size(); ++k) {
    Level& L = *levels_[k];
    L.scalar_interp = interpolation(*L.mesh, *levels_[k + 1]->mesh, comm, rank);
    check(MatCreateMAIJ(L.scalar_interp, 3, &L.interp), "MatCreateMAIJ");
    MatInfo info;
    check(MatGetInfo(L.scalar_interp, MAT_LOCAL, &info), "MatGetInfo");
    L.interp_bytes = std::size_t(info.memory);
  }
}

GeometricMultigrid::~GeometricMultigrid() {
  for (auto& L : levels_) {
    for (Vec* v : {&L->b, &L->x, &L->r, &L->p, &L->t, &L->dinv}) VecDestroy(v);
    MatDestroy(&L->interp);
    MatDestroy(&L->scalar_interp);
    KSPDestroy(&L->coarse);
    L->assembled.reset();
    MatDestroy(&L->pristine);
  }
}

int GeometricMultigrid::levels() const { return int(levels_.size()); }

std::vector<long long> GeometricMultigrid::level_nodes() const {
  std::vector<long long> n;
  for (const auto& L : levels_) n.push_back(L->mesh->nodes());
  return n;
}

std::size_t GeometricMultigrid::memory_bytes() const {
  std::size_t bytes = 0;
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    const Level& L = *levels_[k];
    if (k > 0 && L.mf) bytes += L.mf->memory_bytes();
    bytes += L.interp_bytes + 6 * 3 * std::size_t(L.own_end - L.own_begin) * sizeof(double);
    bytes += L.face_slot.size() * sizeof(std::int32_t);
    if (L.assembled) {
      MatInfo info;
      if (MatGetInfo(L.assembled->mat(), MAT_LOCAL, &info) == 0) bytes += 2 * std::size_t(info.memory);  // and the pristine K
    }
  }
  return bytes;
}

std::string GeometricMultigrid::describe() const {
  std::string s = std::to_string(levels_.size()) + " levels (";
  for (std::size_t k = 0; k < levels_.size(); ++k) s += (k ? ", " : "") + std::to_string(levels_[k]->mesh->nodes());
  s += " nodes), Chebyshev degree " + std::to_string(set_.degree) + (set_.single ? " in float" : "") +
       (coarse_amg_ ? ", coarsest by AMG" : ", coarsest factored");
  return s;
}

void GeometricMultigrid::attach(PC pc) {
  check(PCSetType(pc, PCSHELL), "PCSetType");
  check(PCShellSetContext(pc, this), "PCShellSetContext");
  check(PCShellSetApply(pc, &shell_apply), "PCShellSetApply");
  check(PCShellSetName(pc, "geometric multigrid (wetroad)"), "PCShellSetName");
}

PetscErrorCode GeometricMultigrid::shell_apply(PC pc, Vec b, Vec x) {
  void* ctx = nullptr;
  PetscCall(PCShellGetContext(pc, &ctx));
  try {
    static_cast<GeometricMultigrid*>(ctx)->apply(b, x);
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
  return 0;
}

void GeometricMultigrid::update() {
  const double t0 = MPI_Wtime();
  // Level 0's masks: its eliminated rows, gathered over the ranks by face and top node.
  Level& F = *levels_[0];
  {
    const PetscInt first = 3 * PetscInt(F.own_begin);
    std::vector<char> flag(3 * std::size_t(F.own_end - F.own_begin), 0);
    for (PetscInt r : F.mf->eliminated()) flag[std::size_t(r - first)] = 1;
    auto mask_of = [&](std::int32_t id) {
      unsigned char m = 0;
      if (id < F.own_begin || id >= F.own_end) return m;
      for (int c = 0; c < 3; ++c) m |= (flag[3 * std::size_t(id - F.own_begin) + c] ? 1 : 0) << c;
      return m;
    };
    std::fill(F.face_mask.begin(), F.face_mask.end(), 0);
    std::fill(F.top_mask.begin(), F.top_mask.end(), 0);
    for (int j = 0; j <= F.ny(); ++j)
      for (int i = 0; i <= F.nx(); ++i) F.face_mask[std::size_t(j) * (F.nx() + 1) + i] = mask_of(F.mesh->node(0, i, j));
    for (int j = 0; j <= F.top_ny(); ++j)
      for (int i = 0; i <= F.top_nx(); ++i)
        F.top_mask[std::size_t(j) * (F.top_nx() + 1) + i] = mask_of(F.mesh->node(F.top_plane(), i, j));
    MPI_Allreduce(MPI_IN_PLACE, F.face_mask.data(), int(F.face_mask.size()), MPI_UNSIGNED_CHAR, MPI_BOR, comm_);
    MPI_Allreduce(MPI_IN_PLACE, F.top_mask.data(), int(F.top_mask.size()), MPI_UNSIGNED_CHAR, MPI_BOR, comm_);
  }
  // The bounds of every level are estimated again whenever the fine frames change (each
  // Signorini iteration), all levels together: so they depend only on the operators of that
  // moment, not on what came before, and a run restarted from a checkpoint smooths exactly as
  // the uninterrupted one. The coarsest level is refactored then too, and keeps its constraints
  // through the active-set iterations in between (a factorisation per active-set change cost
  // more than the CG iterations it saved: 32 s against 8 s for AMG on a 3k-node shear test).
  const bool estimate = F.mf->frames_version() != F.frames_seen;
  F.frames_seen = F.mf->frames_version();
  for (std::size_t k = 1; k < levels_.size(); ++k)
    if (k + 1 < levels_.size() || estimate) derive_constraints(k);
  for (std::size_t k = 0; k + 1 < levels_.size(); ++k) {
    Level& L = *levels_[k];
    L.mf->diagonal(L.dinv);
    check(VecReciprocal(L.dinv), "VecReciprocal");
    if (estimate) estimate_bounds(L);
  }
  wall_update_ += MPI_Wtime() - t0;
}

void GeometricMultigrid::derive_constraints(std::size_t k) {
  Level& C = *levels_[k];
  const Level& F = *levels_[k - 1];
  const std::vector<double>& ff = F.current_frames();
  // The fine node at (or nearest) each coarse face and top node's place (the levels nest on the
  // face where the counts halve exactly; half_even's rounding moves a node by less than a cell).
  std::vector<double> frames(9 * C.face_mask.size());
  for (int j = 0; j <= C.ny(); ++j)
    for (int i = 0; i <= C.nx(); ++i) {
      const std::size_t c = std::size_t(j) * (C.nx() + 1) + i;
      const std::size_t f = std::size_t(nearest(j, C.ny(), F.ny())) * (F.nx() + 1) + nearest(i, C.nx(), F.nx());
      C.face_mask[c] = F.face_mask[f];
      std::copy(&ff[9 * f], &ff[9 * f] + 9, &frames[9 * c]);
    }
  for (int j = 0; j <= C.top_ny(); ++j)
    for (int i = 0; i <= C.top_nx(); ++i) {
      const std::size_t f = std::size_t(nearest(j, C.top_ny(), F.top_ny())) * (F.top_nx() + 1) + nearest(i, C.top_nx(), F.top_nx());
      C.top_mask[std::size_t(j) * (C.top_nx() + 1) + i] = F.top_mask[f];
    }
  std::vector<PetscInt> rows;
  auto add = [&](std::int32_t id, unsigned char m) {
    if (id < C.own_begin || id >= C.own_end) return;
    for (int c = 0; c < 3; ++c)
      if (m >> c & 1) rows.push_back(3 * PetscInt(id) + c);
  };
  for (int j = 0; j <= C.ny(); ++j)
    for (int i = 0; i <= C.nx(); ++i) add(C.mesh->node(0, i, j), C.face_mask[std::size_t(j) * (C.nx() + 1) + i]);
  for (int j = 0; j <= C.top_ny(); ++j)
    for (int i = 0; i <= C.top_nx(); ++i)
      add(C.mesh->node(C.top_plane(), i, j), C.top_mask[std::size_t(j) * (C.top_nx() + 1) + i]);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  if (C.mf) {
    if (frames != C.mf->frames()) C.mf->set_frames(frames);
    C.mf->set_eliminated(std::move(rows), C.unit_diag);
    return;
  }
  // The coarsest level: refactored only when its frames or constraints changed. Without
  // coarse_constraints it keeps the global frames and only the top's and the pins' constraints
  // (components x and y on the face), so that one factorisation serves the whole run.
  if (!set_.coarse_constraints) {
    std::fill(frames.begin(), frames.end(), 0.0);
    for (std::size_t q = 0; q < frames.size(); q += 9) frames[q] = frames[q + 4] = frames[q + 8] = 1.0;
    rows.erase(std::remove_if(rows.begin(), rows.end(),
                              [&](PetscInt r) {
                                const std::int32_t id = std::int32_t(r / 3);
                                return C.face_slot[std::size_t(id)] >= 0 && r % 3 == 2;
                              }),
               rows.end());
  }
  int same = frames == C.factored_frames && rows == C.factored_rows;
  MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_LAND, comm_);
  if (same) return;
  // Rotated from the pristine matrix, not from the last frames: the factor then depends on
  // these frames alone (a restarted run refactors the same matrix to the bit).
  C.assembled->reset(C.pristine);
  C.assembled->set_frames(frames);
  check(VecSet(C.x, 0.0), "VecSet");
  C.assembled->eliminate(rows, C.unit_diag, C.x, C.b, nullptr);
  C.frames = frames;
  C.eliminated = rows;
  C.factored_frames = std::move(frames);
  C.factored_rows = std::move(rows);
  check(KSPSetOperators(C.coarse, C.assembled->mat(), C.assembled->mat()), "KSPSetOperators");
  check(KSPSetUp(C.coarse), "KSPSetUp");
}

void GeometricMultigrid::estimate_bounds(Level& L) {
  // Lanczos through CG on D^-1 A (x: z, t: A p): its coefficients give the tridiagonal matrix
  // whose largest eigenvalue converges to D^-1 A's from below, fast (Saad, Iterative Methods,
  // sec. 6.7.3; PETSc's KSPChebyshev estimates the same way).
  PetscInt first = 0;
  check(VecGetOwnershipRange(L.r, &first, nullptr), "VecGetOwnershipRange");
  {
    PetscScalar* a;
    PetscInt n = 0;
    check(VecGetLocalSize(L.r, &n), "VecGetLocalSize");
    check(VecGetArray(L.r, &a), "VecGetArray");
    for (PetscInt i = 0; i < n; ++i) a[i] = start_value(first + i);
    check(VecRestoreArray(L.r, &a), "VecRestoreArray");
  }
  const int m = set_.estimate_steps;
  std::vector<double> alpha, beta;
  check(VecPointwiseMult(L.x, L.dinv, L.r), "VecPointwiseMult");
  check(VecCopy(L.x, L.p), "VecCopy");
  PetscScalar rho = 0;
  check(VecDot(L.r, L.x, &rho), "VecDot");
  for (int it = 0; it < m && rho > 0; ++it) {
    L.mf->multiply(L.p, L.t);
    PetscScalar pq = 0;
    check(VecDot(L.p, L.t, &pq), "VecDot");
    if (!(pq > 0)) break;
    const double a = rho / pq;
    check(VecAXPY(L.r, -a, L.t), "VecAXPY");
    check(VecPointwiseMult(L.x, L.dinv, L.r), "VecPointwiseMult");
    PetscScalar rho_new = 0;
    check(VecDot(L.r, L.x, &rho_new), "VecDot");
    const double bt = rho_new / rho;
    alpha.push_back(a);
    beta.push_back(bt);
    check(VecAYPX(L.p, bt, L.x), "VecAYPX");
    rho = rho_new;
  }
  const int n = int(alpha.size());
  if (n == 0) {
    L.lambda = 2.0;  // a safe bound for a Jacobi-scaled operator of this kind (Gershgorin-like)
    return;
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    T(i, i) = 1 / alpha[std::size_t(i)] + (i > 0 ? beta[std::size_t(i) - 1] / alpha[std::size_t(i) - 1] : 0.0);
    if (i + 1 < n) T(i, i + 1) = T(i + 1, i) = std::sqrt(beta[std::size_t(i)]) / alpha[std::size_t(i)];
  }
  L.lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}

void GeometricMultigrid::chebyshev(Level& L, Vec b, Vec x, bool zero_guess) {
  // Chebyshev iteration on [lo, hi] x lambda with the Jacobi preconditioner (Saad, Alg. 12.1),
  // each step's vector updates fused into one pass after its product:
  //   r = b - A x,  p = c1 D^-1 r + c2 p,  x = x + p.
  const double hi = set_.esteig_hi * L.lambda, lo = set_.esteig_lo * L.lambda;
  const double theta = 0.5 * (hi + lo), delta = 0.5 * (hi - lo);
  auto step = [&](bool residual, bool first, double c1, double c2) {
    const PetscScalar *ba = nullptr, *da = nullptr;
    PetscScalar *ra = nullptr, *pa = nullptr, *xa = nullptr;
    PetscInt n = 0;
    check(VecGetLocalSize(x, &n), "VecGetLocalSize");
    check(VecGetArrayRead(b, &ba), "VecGetArrayRead");
    check(VecGetArrayRead(L.dinv, &da), "VecGetArrayRead");
    check(VecGetArray(L.r, &ra), "VecGetArray");
    check(VecGetArray(L.p, &pa), "VecGetArray");
    check(VecGetArray(x, &xa), "VecGetArray");
    for (PetscInt i = 0; i < n; ++i) {
      const double r = residual ? ba[i] - ra[i] : ba[i];
      const double p = first ? (da[i] * r) * c1 : c1 * (da[i] * r) + c2 * pa[i];
      pa[i] = p;
      xa[i] = residual ? xa[i] + p : p;
    }
    check(VecRestoreArray(x, &xa), "VecRestoreArray");
    check(VecRestoreArray(L.p, &pa), "VecRestoreArray");
    check(VecRestoreArray(L.r, &ra), "VecRestoreArray");
    check(VecRestoreArrayRead(L.dinv, &da), "VecRestoreArrayRead");
    check(VecRestoreArrayRead(b, &ba), "VecRestoreArrayRead");
  };
  if (!zero_guess) L.mf->multiply_with(x, L.r, set_.single);
  step(!zero_guess, true, 1.0 / theta, 0.0);
  double rho_old = delta / theta;
  for (int k = 1; k < set_.degree; ++k) {
    L.mf->multiply_with(x, L.r, set_.single);
    const double rho = 1.0 / (2.0 * theta / delta - rho_old);
    step(true, false, 2.0 * rho / delta, rho * rho_old);
    rho_old = rho;
  }
}

void GeometricMultigrid::restrict_to(std::size_t k, Vec fine_r, Vec coarse_b) {
  Level& F = *levels_[k];
  Level& C = *levels_[k + 1];
  check(VecCopy(fine_r, F.t), "VecCopy");
  zero_rows(F.t, F.current_eliminated(), 3 * PetscInt(F.own_begin));
  rotate_face_dofs(F.t, F.own_begin, F.own_end, F.face_slot, F.current_frames(), false);
  check(MatMultTranspose(F.interp, F.t, coarse_b), "MatMultTranspose");
  rotate_face_dofs(coarse_b, C.own_begin, C.own_end, C.face_slot, C.current_frames(), true);
  zero_rows(coarse_b, C.current_eliminated(), 3 * PetscInt(C.own_begin));
}

void GeometricMultigrid::prolong_add(std::size_t k, Vec coarse_x, Vec fine_x) {
  Level& F = *levels_[k];
  Level& C = *levels_[k + 1];
  check(VecCopy(coarse_x, C.t), "VecCopy");
  zero_rows(C.t, C.current_eliminated(), 3 * PetscInt(C.own_begin));
  rotate_face_dofs(C.t, C.own_begin, C.own_end, C.face_slot, C.current_frames(), false);
  check(MatMult(F.interp, C.t, F.t), "MatMult");
  rotate_face_dofs(F.t, F.own_begin, F.own_end, F.face_slot, F.current_frames(), true);
  zero_rows(F.t, F.current_eliminated(), 3 * PetscInt(F.own_begin));
  check(VecAXPY(fine_x, 1.0, F.t), "VecAXPY");
}

void GeometricMultigrid::vcycle(std::size_t k, Vec b, Vec x) {
  Level& L = *levels_[k];
  double t0 = MPI_Wtime();
  if (k + 1 == levels_.size()) {
    check(KSPSolve(L.coarse, b, x), "KSPSolve");
    L.seconds += MPI_Wtime() - t0;
    return;
  }
  chebyshev(L, b, x, true);
  L.mf->multiply_with(x, L.r, set_.single);
  check(VecAYPX(L.r, -1.0, b), "VecAYPX");
  Level& C = *levels_[k + 1];
  restrict_to(k, L.r, C.b);
  L.seconds += MPI_Wtime() - t0;
  vcycle(k + 1, C.b, C.x);
  t0 = MPI_Wtime();
  prolong_add(k, C.x, x);
  chebyshev(L, b, x, false);
  L.products += 2 * set_.degree;
  L.seconds += MPI_Wtime() - t0;
}

std::string GeometricMultigrid::timing() const {
  std::string s;
  char buf[160];
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    const Level& L = *levels_[k];
    std::snprintf(buf, sizeof buf, "%slevel %zu: %.2f s (%ld products)", k ? ", " : "", k, L.seconds, L.products);
    s += buf;
  }
  return s;
}

void GeometricMultigrid::apply(Vec b, Vec x) { vcycle(0, b, x); }

}  // namespace wr
