#include "lib/fem/elastic_block_impl.hpp"

namespace wr {

using petsc::check;

namespace block_detail {
namespace {

// CG's default test (residual below rtol x the right-hand side) plus a least reduction of the
// solve's own initial residual. Why: a loose tolerance tied to the last relative change fed
// back on itself. A large change made the next solve so loose that CG, warm-started, stopped
// after 2 iterations; that barely moved u, reported a small change, and made the solve after it
// tight again. On the 300 x 300 obstacle every second Signorini iteration was such a non-step
// (2 against 50 CG iterations; change 7e-3 against 4e-2).
struct LeastReductionTest {
  void* default_test = nullptr;
  double least_reduction = 0.1;  // the residual must fall below this x its initial value
  double initial = 0;
};

PetscErrorCode least_reduction_converged(KSP ksp, PetscInt n, PetscReal rnorm, KSPConvergedReason* reason, void* ctx) {
  auto* t = static_cast<LeastReductionTest*>(ctx);
  PetscCall(KSPConvergedDefault(ksp, n, rnorm, reason, t->default_test));
  if (n == 0) t->initial = rnorm;
  if (*reason > 0 && rnorm > t->least_reduction * t->initial) *reason = KSP_CONVERGED_ITERATING;
  return 0;
}

PetscErrorCode least_reduction_destroy(void* ctx) {
  auto* t = static_cast<LeastReductionTest*>(ctx);
  PetscCall(KSPConvergedDefaultDestroy(t->default_test));
  delete t;
  return 0;
}

}  // namespace

void set_default_option(const char* name, const char* value) {
  PetscBool given = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, name, &given);
  if (!given) PetscOptionsSetValue(nullptr, name, value);
}

double nodes_on_this_host(MPI_Comm comm, double nodes) {
  int ranks = 1, host_ranks = 1;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm host;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  MPI_Comm_size(host, &host_ranks);
  MPI_Comm_free(&host);
  return nodes * double(host_ranks) / double(ranks);
}

// The test of the next solves: the default one, or with a least reduction (> 0).
void set_convergence_test(KSP ksp, double least_reduction) {
  void* dflt = nullptr;
  check(KSPConvergedDefaultCreate(&dflt), "KSPConvergedDefaultCreate");
  if (least_reduction <= 0) {
    check(KSPSetConvergenceTest(ksp, KSPConvergedDefault, dflt, KSPConvergedDefaultDestroy), "KSPSetConvergenceTest");
    return;
  }
  auto* t = new LeastReductionTest{dflt, least_reduction, 0.0};
  check(KSPSetConvergenceTest(ksp, least_reduction_converged, t, least_reduction_destroy), "KSPSetConvergenceTest");
}

ElementMatrix brick_stiffness(double hx, double hy, double hz, double E, double nu) {
  const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  ElementMatrix K{};
  const double g = 1.0 / std::sqrt(3.0);
  for (int gz = 0; gz < 2; ++gz)
    for (int gy = 0; gy < 2; ++gy)
      for (int gx = 0; gx < 2; ++gx) {
        const double xi[3] = {gx ? g : -g, gy ? g : -g, gz ? g : -g};
        double dN[8][3];  // physical gradients
        for (int a = 0; a < 8; ++a) {
          const int s[3] = {(a & 1) ? 1 : -1, (a & 2) ? 1 : -1, (a & 4) ? 1 : -1};
          const double f[3] = {1 + s[0] * xi[0], 1 + s[1] * xi[1], 1 + s[2] * xi[2]};
          dN[a][0] = s[0] * f[1] * f[2] / 8 * (2 / hx);
          dN[a][1] = s[1] * f[0] * f[2] / 8 * (2 / hy);
          dN[a][2] = s[2] * f[0] * f[1] / 8 * (2 / hz);
        }
        const double w = hx * hy * hz / 8;  // det J times the unit Gauss weights
        for (int a = 0; a < 8; ++a)
          for (int b = 0; b < 8; ++b)
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j) {
                // K_aibj = lam dNa_i dNb_j + mu (dNa_j dNb_i + delta_ij grad Na . grad Nb)
                double v = lam * dN[a][i] * dN[b][j] + mu * dN[a][j] * dN[b][i];
                if (i == j) v += mu * (dN[a][0] * dN[b][0] + dN[a][1] * dN[b][1] + dN[a][2] * dN[b][2]);
                K[(a * 3 + i) * 24 + b * 3 + j] += w * v;
              }
      }
  return K;
}

}  // namespace block_detail

void ElasticBlock::Impl::make_grid() {
  int ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  try {
    mesh = std::make_unique<GradedMesh>(spec.mesh, ranks);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("block mesh: ") + e.what());
  }
  own_begin = mesh->owned_begin(rank);
  own_end = mesh->owned_end(rank);
}

Mat block_detail::assemble_stiffness(const GradedMesh& g, MPI_Comm comm, double young, double poisson) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::int32_t own_begin = g.owned_begin(rank), own_end = g.owned_end(rank);
  auto owns = [&](std::int32_t id) { return id >= own_begin && id < own_end; };
  auto dof = [](std::int32_t id, int c) { return 3 * PetscInt(id) + c; };
  auto for_each_brick = [&](auto&& f) { wr::for_each_local_brick(g, rank, own_begin, own_end, f); };
  const PetscInt n_own = own_end - own_begin;
  std::vector<std::vector<std::int32_t>> cols(static_cast<std::size_t>(n_own));
  for_each_brick([&](int, const std::vector<std::int32_t>& ids, const std::vector<double>&) {
    for (std::int32_t r : ids)
      if (owns(r)) {
        auto& v = cols[std::size_t(r - own_begin)];
        v.insert(v.end(), ids.begin(), ids.end());
      }
  });
  std::vector<PetscInt> d_nnz(3 * std::size_t(n_own)), o_nnz(3 * std::size_t(n_own));
  for (PetscInt r = 0; r < n_own; ++r) {
    auto& v = cols[std::size_t(r)];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    PetscInt d = 0;
    for (std::int32_t c : v) d += owns(c);
    for (int c = 0; c < 3; ++c) {
      d_nnz[3 * r + c] = 3 * d;
      o_nnz[3 * r + c] = 3 * (PetscInt(v.size()) - d);
    }
    std::vector<std::int32_t>().swap(v);
  }
  Mat K = nullptr;
  check(MatCreate(comm, &K), "MatCreate");
  check(MatSetSizes(K, 3 * n_own, 3 * n_own, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(K, MATAIJ), "MatSetType");
  check(MatSetBlockSize(K, 3), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocation(K, 0, d_nnz.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(K, 0, d_nnz.data(), 0, o_nnz.data()), "MatMPIAIJSetPreallocation");
  check(MatSetOption(K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");

  std::vector<ElementMatrix> layer_k;
  for (int e = 0; e < g.layers(); ++e) {
    const int l = g.layer_level(e);
    layer_k.push_back(brick_stiffness(g.hx(l), g.hy(l), g.planes()[e + 1].z - g.planes()[e].z, young, poisson));
  }
  std::vector<double> ke;
  std::vector<PetscInt> rows, colidx;
  for_each_brick([&](int e, const std::vector<std::int32_t>& ids, const std::vector<double>& w) {
    const ElementMatrix& k8 = layer_k[std::size_t(e)];
    const std::size_t n = ids.size(), m3 = 3 * n;
    ke.assign(m3 * m3, 0.0);
    for (int a = 0; a < 8; ++a)
      for (std::size_t p = 0; p < n; ++p) {
        const double wa = w[a * n + p];
        if (wa == 0) continue;
        for (int b = 0; b < 8; ++b)
          for (std::size_t q = 0; q < n; ++q) {
            const double wab = wa * w[b * n + q];
            if (wab == 0) continue;
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j) ke[(3 * p + i) * m3 + 3 * q + j] += wab * k8[(a * 3 + i) * 24 + b * 3 + j];
          }
      }
    colidx.clear();
    for (std::int32_t id : ids)
      for (int c = 0; c < 3; ++c) colidx.push_back(dof(id, c));
    for (std::size_t p = 0; p < n; ++p) {
      if (!owns(ids[p])) continue;
      rows.assign({dof(ids[p], 0), dof(ids[p], 1), dof(ids[p], 2)});
      check(MatSetValues(K, 3, rows.data(), PetscInt(m3), colidx.data(), &ke[3 * p * m3], ADD_VALUES),
            "MatSetValues");
    }
  });
  check(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return K;
}

void ElasticBlock::Impl::assemble() {
  const GradedMesh& g = *mesh;
  Mat K = nullptr;
  if (solver == LinearSolver::gmg) check(VecCreateMPI(comm, 3 * (own_end - own_begin), PETSC_DETERMINE, &u), "VecCreateMPI");
  else {
    K = assemble_stiffness(g, comm, spec.young, spec.poisson);
    check(MatCreateVecs(K, &u, nullptr), "MatCreateVecs");
  }
  check(VecSet(u, 0.0), "VecSet");

  face_slot.assign(std::size_t(g.nodes()), -1);
  for (int j = 0; j <= face_ny(); ++j)
    for (int i = 0; i <= face_nx(); ++i) face_slot[std::size_t(g.node(0, i, j))] = j * (face_nx() + 1) + i;
  // Scatter of the whole face (all ranks receive all of it).
  std::vector<PetscInt> idx;
  for (int j = 0; j <= face_ny(); ++j)
    for (int i = 0; i <= face_nx(); ++i)
      for (int c = 0; c < 3; ++c) idx.push_back(dof(g.node(0, i, j), c));
  IS is;
  check(ISCreateGeneral(PETSC_COMM_SELF, PetscInt(idx.size()), idx.data(), PETSC_COPY_VALUES, &is), "ISCreateGeneral");
  check(VecCreateSeq(PETSC_COMM_SELF, PetscInt(idx.size()), &face_u), "VecCreateSeq");
  check(VecScatterCreate(u, is, face_u, nullptr, &face_scatter), "VecScatterCreate");
  ISDestroy(&is);
  if (K) {
    stiffness = std::make_unique<FramedStiffness>(K, own_begin, own_end, face_slot);
    return;
  }
  auto mf = std::make_unique<MatrixFreeFramed>(g, comm, spec.young, spec.poisson, face_slot);
  matrix_free = mf.get();
  stiffness = std::move(mf);
  gmg = std::make_unique<GeometricMultigrid>(spec.mesh, g, *matrix_free, comm, spec.young, spec.poisson,
                                             gmg_settings_from_options());
}

}  // namespace wr
