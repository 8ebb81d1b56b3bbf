#include "lib/fem/elastic_block.hpp"

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <utility>

#include "lib/contact/adaptive_damping.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/fem/framed_stiffness.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/fem/penetration_retries.hpp"
#include "lib/fem/slow_mode_extrapolation.hpp"
#include "lib/io/vtu_writer.hpp"

namespace wr {

namespace {

using petsc::check;

// A solver default that a user's -option (command line, --petsc) overrides.
void set_default_option(const char* name, const char* value) {
  PetscBool given = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, name, &given);
  if (!given) PetscOptionsSetValue(nullptr, name, value);
}

// A solver default that lives as long as this object and is removed after it, unless the user
// gave it. Why scoped: PETSc's options database is process-wide, and a process may hold blocks
// of both hierarchies (tests, nested iteration, the mesh-convergence bench).
class ScopedDefaultOption {
 public:
  ScopedDefaultOption(const char* name, const char* value) : name_(name) {
    PetscBool given = PETSC_FALSE;
    PetscOptionsHasName(nullptr, nullptr, name, &given);
    if (!given) set_ = PetscOptionsSetValue(nullptr, name, value) == 0;
  }
  ~ScopedDefaultOption() {
    if (set_) PetscOptionsClearValue(nullptr, name_);
  }
  ScopedDefaultOption(const ScopedDefaultOption&) = delete;
  ScopedDefaultOption& operator=(const ScopedDefaultOption&) = delete;

 private:
  const char* name_;
  bool set_ = false;
};

// The nodes owned by the ranks of `comm` that share this host (the ranks split the nodes about
// equally: x-slabs with equal shares of the face).
double nodes_on_this_host(MPI_Comm comm, double nodes) {
  int ranks = 1, host_ranks = 1;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm host;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  MPI_Comm_size(host, &host_ranks);
  MPI_Comm_free(&host);
  return nodes * double(host_ranks) / double(ranks);
}

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

using ElementMatrix = std::array<double, 24 * 24>;

// Stiffness of an axis-aligned Q1 brick (hx, hy, hz), 2x2x2 Gauss (exact for the brick).
// Local node a = ia + 2 ja + 4 ka, dof a*3 + c.
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

struct FaceNode {
  std::int32_t i, j;
  PetscInt row[3];  // global dofs
  Vec3 x0;          // reference position
  Vec3 normal{0, 0, 1};  // obstacle normal N of the current linearisation
  double g = -INFINITY;  // bound on N . u (-inf: no obstacle within reach)
};

// The contact face's in-plane rigid modes (FaceModeExtrapolation): slide x, slide y,
// dilatation and twist about the face centre, the last two scaled by the face's rms radius so
// that every coordinate is a displacement (m). They are orthogonal on the face lattice, so each
// coordinate is a projection.
struct FaceModeBasis {
  double xc, yc, radius = 1;  // m; the radius only computed when `on`
  FaceModeBasis(const GradedMesh& g, double lx, double ly, int fnx, int fny, bool on) : xc(0.5 * lx), yc(0.5 * ly) {
    if (!on) return;
    double sum = 0;
    for (int j = 0; j <= fny; ++j)
      for (int i = 0; i <= fnx; ++i) {
        const Vec3 p = g.position(0, i, j);
        sum += (p.x - xc) * (p.x - xc) + (p.y - yc) * (p.y - yc);
      }
    radius = std::sqrt(sum / double((fnx + 1) * (fny + 1)));
  }
  // In-plane shape {x, y} of mode k at (x, y).
  std::array<double, 2> shape(double x, double y, int k) const {
    const double rx = (x - xc) / radius, ry = (y - yc) / radius;
    switch (k) {
      case 0: return {1, 0};
      case 1: return {0, 1};
      case 2: return {rx, ry};
      default: return {-ry, rx};
    }
  }
};

}  // namespace

// Householder reflection with Q e_z = n (symmetric, orthogonal), row-major.
std::array<double, 9> frame_of(const Vec3& n) {
  std::array<double, 9> q{1, 0, 0, 0, 1, 0, 0, 0, 1};
  const Vec3 w{-n.x, -n.y, 1 - n.z};  // e_z - n
  const double ww = w.dot(w);
  if (ww < 1e-30) return q;
  const double wv[3] = {w.x, w.y, w.z};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q[r * 3 + c] -= 2 * wv[r] * wv[c] / ww;
  return q;
}

struct ElasticBlock::Impl {
  BlockSpec spec;
  MPI_Comm comm = MPI_COMM_NULL;
  AmgHierarchy amg = AmgHierarchy::standard;  // spec.amg resolved for this mesh and host
  std::unique_ptr<GradedMesh> mesh;
  int rank = 0;
  PetscInt own_begin = 0, own_end = 0;  // owned node ids
  // Khat = R^T K R in the face nodes' current constraint frames, reduced in place by the
  // active-set solves (lib/fem/framed_stiffness.hpp); K itself is not kept.
  std::unique_ptr<FramedStiffness> stiffness;
  Vec u = nullptr;  // current displacement, carried from load step to load step
  // The whole contact face, gathered on every rank (normals need the neighbours' positions).
  VecScatter face_scatter = nullptr;
  Vec face_u = nullptr;
  std::vector<char> active;  // per owned face node, carried between solves
  std::vector<std::int32_t> face_slot;  // per node id: its face index j (nx+1) + i, or -1

  PetscInt dof(std::int32_t node, int c) const { return 3 * PetscInt(node) + c; }
  bool owns(std::int32_t node) const { return node >= own_begin && node < own_end; }
  int face_nx() const { return spec.mesh.nx; }
  int face_ny() const { return spec.mesh.ny; }

  // Calls f(layer, ids, weights) for every brick that touches an owned node: ids = the distinct
  // independent nodes behind the 8 corners, weights = 8 x ids.size() (row-major) interpolation.
  template <class F>
  void for_each_local_brick(F&& f) const {
    const GradedMesh& g = *mesh;
    std::vector<GradedMesh::Parent> ps;
    std::vector<std::int32_t> ids;
    std::vector<double> w;
    for (int e = 0; e < g.layers(); ++e) {
      const int l = g.layer_level(e);
      // Hanging parents lie at most one cell beyond a brick: two cells of margin suffice.
      const int i0 = std::max(0, g.owned_i_begin(rank, l) - 2);
      const int i1 = std::min(g.cells_x(l), g.owned_i_end(rank, l) + 2);
      for (int j = 0; j < g.cells_y(l); ++j)
        for (int i = i0; i < i1; ++i) {
          ids.clear();
          bool mine = false;
          int start[9];
          ps.clear();
          for (int c = 0; c < 8; ++c) {
            int p, pi, pj;
            g.corner(e, i, j, c, p, pi, pj);
            start[c] = int(ps.size());
            g.parents(p, pi, pj, ps);
          }
          start[8] = int(ps.size());
          for (const auto& q : ps) {
            if (std::find(ids.begin(), ids.end(), q.id) == ids.end()) ids.push_back(q.id);
            mine |= owns(q.id);
          }
          if (!mine) continue;
          w.assign(8 * ids.size(), 0.0);
          for (int c = 0; c < 8; ++c)
            for (int k = start[c]; k < start[c + 1]; ++k)
              w[c * ids.size() + (std::find(ids.begin(), ids.end(), ps[k].id) - ids.begin())] += ps[k].weight;
          f(e, ids, w);
        }
    }
  }

  void make_grid() {
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

  // Exact preallocation (rows of owned nodes only; every rank assembles its own rows from the
  // bricks around them, so no entries travel between ranks), then the brick matrices through
  // the hanging-node interpolation: K = sum_e C_e^T K_e C_e.
  void assemble() {
    const PetscInt n_own = own_end - own_begin;
    std::vector<std::vector<std::int32_t>> cols(static_cast<std::size_t>(n_own));
    for_each_local_brick([&](int, const std::vector<std::int32_t>& ids, const std::vector<double>&) {
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

    const GradedMesh& g = *mesh;
    std::vector<ElementMatrix> layer_k;
    for (int e = 0; e < g.layers(); ++e) {
      const int l = g.layer_level(e);
      layer_k.push_back(brick_stiffness(g.hx(l), g.hy(l), g.planes()[e + 1].z - g.planes()[e].z, spec.young,
                                        spec.poisson));
    }
    std::vector<double> ke;
    std::vector<PetscInt> rows, colidx;
    for_each_local_brick([&](int e, const std::vector<std::int32_t>& ids, const std::vector<double>& w) {
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
    check(MatCreateVecs(K, &u, nullptr), "MatCreateVecs");
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
    stiffness = std::make_unique<FramedStiffness>(K, own_begin, own_end, face_slot);
  }

  void gather_face() const {
    check(VecScatterBegin(face_scatter, u, face_u, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(face_scatter, u, face_u, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  }

  // ---- The phases of one solve() (Algorithm 1), defined below it ----
  // The prescribed top dofs (and, under a frictionless top, the minimal pins of two face
  // corners), and the rows whose reactions are the top's forces.
  struct TopBoundary {
    std::vector<PetscInt> fixed_rows;
    std::vector<double> fixed_vals;
    std::vector<PetscInt> top_rows[3];
  };
  // The working set of a solve: vectors in the rotated frames, and CG preconditioned by GAMG
  // (the operator is `stiffness`).
  struct LinearSystems {
    Vec uh = nullptr, b = nullptr, r = nullptr, diag = nullptr, ustar = nullptr;
    KSP ksp = nullptr;
    Vec before_jump = nullptr;  // the iterate before the last slow-mode jump
    std::vector<double> q_all, q_mine;  // constraint frames, 9 per face slot (all face nodes)
    int first_its = -1;                 // CG iterations with a fresh preconditioner
    // Lean hierarchy: PtAP all at once (no symbolic scratch), for as long as these systems live.
    std::unique_ptr<ScopedDefaultOption> ptap_option;
    LinearSystems(MPI_Comm comm, Vec like, std::size_t face_nodes, AmgHierarchy amg);
    ~LinearSystems();
    LinearSystems(const LinearSystems&) = delete;
    LinearSystems& operator=(const LinearSystems&) = delete;
  };
  struct ActiveSetControl {
    double unit_diag = 1;           // diagonal of eliminated rows
    bool loose = false;             // a loose solve: its first system cuts the residual tenfold
    bool accept_unsettled = false;  // an early linearisation may end with the set still moving
    int max_iterations = 1;
    bool reuse_preconditioner = true;
  };
  struct ActiveSetOutcome {
    bool ok = false, settled = false;  // usable; active set unchanged by the last solve
    std::size_t contact = 0;           // this rank's active face nodes
  };
  struct Correction {
    double change = 0;    // |u* - u| / |u*| on the face
    double cosine = NAN;  // with the previous correction (NaN: none)
  };

  std::vector<FaceNode> owned_face_nodes() const;
  // Writes the top's prescribed values into u.
  TopBoundary prescribe_top(const ContactLoad& load);
  // Step 1: normal and gap bound of each face node at the current configuration, by a ray cast
  // along the deformed face's normal (thesis Fig. 4.6).
  void linearise(std::vector<FaceNode>& face, const ContactLoad& load) const;
  // Step 2: Khat = R^T K R and uh = R^T u in the nodes' constraint frames; returns the
  // diagonal scale for eliminated rows.
  double rotate_into_frames(const std::vector<FaceNode>& face, LinearSystems& s) const;
  // Step 3: primal-dual active set on the bounds uh_z >= g; the solution is left in s.uh, the
  // rotated reactions in s.r, the contact set in `active`. Counts and failures go into `out`.
  ActiveSetOutcome solve_active_set(const std::vector<FaceNode>& face, const TopBoundary& top, LinearSystems& s,
                                    const ActiveSetControl& control, ContactSolution& out);
  // Step 4: the correction u* - u on the face; prev_corr (3 per face node) becomes this one.
  Correction measure_correction(const std::vector<FaceNode>& face, Vec ustar, std::vector<double>& prev_corr) const;
  // Vertical gaps of this rank's face nodes for the displacement array a (m): their summed
  // separation, the deepest penetration, where that node is, and how many nodes are deeper
  // than load.max_penetration.
  struct FaceGaps {
    double separation = 0, deepest = 0;
    Vec3 deepest_at;
    std::size_t over_limit = 0;
  };
  FaceGaps face_gaps(const std::vector<FaceNode>& face, const PetscScalar* a, const ContactLoad& load) const;
  double deepest_penetration(const std::vector<FaceNode>& face, Vec v, const ContactLoad& load) const;  // collective
  // {Fx, Fy, Fz} on the top face for displacement v (Fz > 0 in compression); `work` is
  // overwritten. Collective.
  std::array<double, 3> top_forces(Vec v, const TopBoundary& top, Vec work) const;
  FaceModeExtrapolation::Modes face_mode_coordinates(const std::vector<FaceNode>& face,
                                                     const FaceModeBasis& basis) const;
  // Adds the modal displacement c through the block, fading linearly to the fixed top.
  void add_face_modes(const FaceModeBasis& basis, const FaceModeExtrapolation::Modes& c);
  // Calls f(x, w, d) for every owned independent node: x its reference position, w = 1 - its
  // height / lz (1 on the face, 0 on the fixed top), d its three entries of u. Shared by the
  // ways of spreading a face displacement through the block (face modes, the coarse start).
  template <class F>
  void for_each_lifted_node(F&& f) {
    const GradedMesh& g = *mesh;
    const PetscInt rstart = 3 * PetscInt(own_begin);
    const auto& planes = g.planes();
    const double z0 = planes.front().z, lz = planes.back().z - z0;
    PetscScalar* a;
    VecGetArray(u, &a);
    for (std::size_t p = 0; p < planes.size(); ++p) {
      const double w = 1 - (planes[p].z - z0) / lz;
      const int nxp = g.cells_x(planes[p].level), nyp = g.cells_y(planes[p].level);
      for (int j = 0; j <= nyp; ++j)
        for (int i = 0; i <= nxp; ++i) {
          const std::int32_t id = planes[p].id[std::size_t(j) * (nxp + 1) + i];
          if (id < 0 || !owns(id)) continue;
          f(g.position(int(p), i, j), w, a + (dof(id, 0) - rstart));
        }
    }
    VecRestoreArray(u, &a);
  }
  // Reactions, separation, penetration and (if asked) the face maps of the final u.
  void output_results(const std::vector<FaceNode>& face, const TopBoundary& top,
                      const std::vector<double>& normal_force, const ContactLoad& load, Vec work,
                      ContactSolution& out) const;
};

ElasticBlock::ElasticBlock(const BlockSpec& spec) : impl_(new Impl) {
  impl_->spec = spec;
  impl_->comm = spec.comm == MPI_COMM_NULL ? PETSC_COMM_WORLD : spec.comm;
  impl_->make_grid();
  impl_->amg = resolve_amg_hierarchy(spec.amg, nodes_on_this_host(impl_->comm, double(impl_->mesh->nodes())),
                                     double(physical_memory_bytes()));
  impl_->assemble();
}

AmgHierarchy ElasticBlock::amg_hierarchy() const { return impl_->amg; }

ElasticBlock::~ElasticBlock() {
  if (impl_->face_scatter) VecScatterDestroy(&impl_->face_scatter);
  if (impl_->face_u) VecDestroy(&impl_->face_u);
  if (impl_->u) VecDestroy(&impl_->u);
  impl_->stiffness.reset();
  delete impl_;
}

const GradedMesh& ElasticBlock::mesh() const { return *impl_->mesh; }

std::size_t ElasticBlock::nodes() const { return std::size_t(impl_->mesh->nodes()); }

BlockState ElasticBlock::state() const {
  const Impl& m = *impl_;
  BlockState s;
  PetscInt n = 0;
  check(VecGetLocalSize(m.u, &n), "VecGetLocalSize");
  const PetscScalar* a;
  check(VecGetArrayRead(m.u, &a), "VecGetArrayRead");
  s.u.assign(a, a + n);
  check(VecRestoreArrayRead(m.u, &a), "VecRestoreArrayRead");
  s.active = m.active;
  return s;
}

void ElasticBlock::restore(const BlockState& s) {
  Impl& m = *impl_;
  PetscInt n = 0;
  check(VecGetLocalSize(m.u, &n), "VecGetLocalSize");
  if (s.u.size() != std::size_t(n))
    throw std::invalid_argument("ElasticBlock::restore: the state was taken from another block");
  PetscScalar* a;
  check(VecGetArray(m.u, &a), "VecGetArray");
  std::copy(s.u.begin(), s.u.end(), a);
  check(VecRestoreArray(m.u, &a), "VecRestoreArray");
  m.active = s.active;
}

std::vector<double> ElasticBlock::face_displacement() const {
  const Impl& m = *impl_;
  const std::size_t nfx = std::size_t(m.face_nx() + 1);
  std::vector<double> local(3 * nfx * std::size_t(m.face_ny() + 1), 0.0), global(local.size());
  const PetscInt rstart = 3 * PetscInt(m.own_begin);
  const PetscScalar* a;
  VecGetArrayRead(m.u, &a);
  for (const FaceNode& f : m.owned_face_nodes())
    for (int c = 0; c < 3; ++c) local[3 * (std::size_t(f.j) * nfx + std::size_t(f.i)) + c] = a[f.row[c] - rstart];
  VecRestoreArrayRead(m.u, &a);
  MPI_Allreduce(local.data(), global.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, m.comm);
  return global;
}

void ElasticBlock::add_lifted_face_field(const std::vector<double>& field, int fnx, int fny) {
  if (fnx < 1 || fny < 1 || field.size() != 3 * std::size_t(fnx + 1) * std::size_t(fny + 1))
    throw std::invalid_argument("add_lifted_face_field: the field is not 3 x (fnx+1) x (fny+1) values");
  const double hx = impl_->spec.mesh.lx / fnx, hy = impl_->spec.mesh.ly / fny;
  impl_->for_each_lifted_node([&](const Vec3& x, double w, PetscScalar* d) {
    if (w <= 0) return;  // the fixed top
    const double sx = std::clamp(x.x / hx, 0.0, double(fnx)), sy = std::clamp(x.y / hy, 0.0, double(fny));
    const int i0 = std::min(int(sx), fnx - 1), j0 = std::min(int(sy), fny - 1);
    const double fx = sx - i0, fy = sy - j0;
    const double wt[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    const std::size_t at[4] = {std::size_t(j0) * (fnx + 1) + i0, std::size_t(j0) * (fnx + 1) + i0 + 1,
                               std::size_t(j0 + 1) * (fnx + 1) + i0, std::size_t(j0 + 1) * (fnx + 1) + i0 + 1};
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      for (int q = 0; q < 4; ++q) v += wt[q] * field[3 * at[q] + c];
      d[c] += w * v;
    }
  });
}

void ElasticBlock::write_vtu(const std::string& path) const {
  const Impl& m = *impl_;
  const GradedMesh& g = *m.mesh;
  VecScatter to_zero;
  Vec all;
  check(VecScatterCreateToZero(m.u, &to_zero, &all), "VecScatterCreateToZero");
  check(VecScatterBegin(to_zero, m.u, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(to_zero, m.u, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  if (m.rank == 0) {
    const PetscScalar* ua;
    VecGetArrayRead(all, &ua);
    std::vector<double> points, disp;
    std::vector<std::int64_t> first(g.planes().size() + 1, 0);  // first point of each plane
    std::vector<GradedMesh::Parent> ps;
    for (std::size_t p = 0; p < g.planes().size(); ++p) {
      const int l = g.planes()[p].level;
      for (int j = 0; j <= g.cells_y(l); ++j)
        for (int i = 0; i <= g.cells_x(l); ++i) {
          const Vec3 x = g.position(int(p), i, j);
          points.insert(points.end(), {x.x, x.y, x.z});
          ps.clear();
          g.parents(int(p), i, j, ps);
          double d[3] = {0, 0, 0};
          for (const auto& q : ps)
            for (int c = 0; c < 3; ++c) d[c] += q.weight * ua[3 * q.id + c];
          disp.insert(disp.end(), {d[0], d[1], d[2]});
        }
      first[p + 1] = first[p] + std::int64_t(g.cells_x(l) + 1) * (g.cells_y(l) + 1);
    }
    VecRestoreArrayRead(all, &ua);
    std::vector<std::int64_t> conn, offsets;
    std::vector<std::uint8_t> types;
    static const int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};  // VTK_HEXAHEDRON corner order
    for (int e = 0; e < g.layers(); ++e) {
      const int l = g.layer_level(e);
      for (int j = 0; j < g.cells_y(l); ++j)
        for (int i = 0; i < g.cells_x(l); ++i) {
          for (int c : vtk_order) {
            int p, pi, pj;
            g.corner(e, i, j, c, p, pi, pj);
            conn.push_back(first[p] + std::int64_t(pj) * (g.cells_x(g.planes()[p].level) + 1) + pi);
          }
          offsets.push_back(std::int64_t(conn.size()));
          types.push_back(12);
        }
    }
    write_vtu_file(path, points, disp, conn, offsets, types);
  }
  VecScatterDestroy(&to_zero);
  VecDestroy(&all);
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

ElasticBlock::Impl::LinearSystems::LinearSystems(MPI_Comm comm, Vec like, std::size_t face_nodes, AmgHierarchy amg)
    : q_all(9 * face_nodes), q_mine(q_all.size()) {
  for (Vec* v : {&uh, &b, &r, &diag, &ustar, &before_jump}) check(VecDuplicate(like, v), "VecDuplicate");
  check(KSPCreate(comm, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
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
  for (Vec* v : {&uh, &b, &r, &diag, &ustar, &before_jump}) VecDestroy(v);
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

double ElasticBlock::Impl::rotate_into_frames(const std::vector<FaceNode>& face, LinearSystems& s) const {
  const int fnx = face_nx();
  std::fill(s.q_mine.begin(), s.q_mine.end(), 0.0);
  for (const FaceNode& f : face) {
    const auto q = frame_of(f.normal);
    std::copy(q.begin(), q.end(), s.q_mine.begin() + 9 * (std::size_t(f.j) * (fnx + 1) + std::size_t(f.i)));
  }
  MPI_Allreduce(s.q_mine.data(), s.q_all.data(), int(s.q_all.size()), MPI_DOUBLE, MPI_SUM, comm);
  stiffness->set_frames(s.q_all);
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
    stiffness->eliminate(rows, control.unit_diag, s.uh, s.b);
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
    const double h = load.obstacle ? load.obstacle->height(p.x, p.y) : 0.0;
    out.separation += std::max(0.0, p.z - h);
    if (h <= p.z) continue;
    // Penetration as a distance: perpendicular to the facet above the node. The vertical depth
    // overstates it by sqrt(1 + slope^2), 2.2x on the slope-2 flanks where the last nodes of
    // the thesis's Problem A sit, and the linearised constraint bounds the normal gap.
    const double depth = (h - p.z) * (load.obstacle ? load.obstacle->normal(p.x, p.y).z : 1.0);
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
      local[nf + idx] = p.z - (load.obstacle ? load.obstacle->height(p.x, p.y) : 0.0);
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

ContactSolution ElasticBlock::solve(const ContactLoad& load) {
  Impl& m = *impl_;
  ContactSolution out;
  out.face_nodes = std::size_t(m.face_nx() + 1) * (m.face_ny() + 1);
  std::vector<FaceNode> face = m.owned_face_nodes();
  if (m.active.size() != face.size()) m.active.assign(face.size(), 0);
  const Impl::TopBoundary top = m.prescribe_top(load);
  Impl::LinearSystems s(m.comm, m.u, out.face_nodes, m.amg);

  // Facet normals make the iteration's map discontinuous (nodes chatter across the kinks), which
  // Aitken's smooth geometric model does not fit: on the demo's 70 % coverage scene the jumps led
  // a shear step to a state 1.4x deeper in the obstacle than allowed. Blend normals only.
  const bool smooth_map = load.follow_geometry && load.obstacle && !load.facet_normals;
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
    const double unit_diag = m.rotate_into_frames(face, s);
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
    if (load.follow_geometry) damping.after_correction(corr.cosine);
    out.history.push_back(change);
    smallest_change = std::min(smallest_change, change);
    if (load.follow_geometry) damping.after_change(out.history);
    const double alpha = load.follow_geometry ? damping.alpha() : 1.0;
    const double step_change = damping.step_change(change);
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
    if (load.trace && m.rank == 0)
      std::fprintf(stderr,
                   "    signorini %3d  change %.3e  alpha %.3f  contact %zu%s  pdas %d  cg %d  rtol %.0e  Fz %.6e  Fx %.6e  pen %.2e  pen* %.2e  [%.1f s]\n",
                   outer + 1, change, alpha, out.contact_nodes, as.settled ? "" : "+", out.active_set_iterations,
                   out.linear_iterations, rtol, trace_fz, trace_fx, trace_pen, trace_pen_star, MPI_Wtime() - t_solve_start);
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
