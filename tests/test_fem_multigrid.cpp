// The geometric multigrid of the FEM (issue 58): its transfers, its symmetry, its mesh-independent
// convergence, and the contact states it reaches against AMG's. Runs on 1 and 2 ranks (ctest).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "lib/contact/periodic_obstacle.hpp"
#include "lib/fem/elastic_block.hpp"
#include "lib/fem/geometric_multigrid.hpp"
#include "lib/fem/graded_mesh.hpp"
#include "lib/fem/matrix_free_framed.hpp"
#include "tests/hertz_check.hpp"

namespace wr {
namespace {

double linear_field(const Vec3& p) { return 0.3 + 2.0 * p.x - 1.5 * p.y + 0.7 * p.z; }

// Trilinear interpolation reproduces linear fields exactly, through hanging nodes too: the
// transfers between the levels then carry rigid motions and uniform strains unchanged.
TEST(GradedMesh, InterpolationReproducesLinearFields) {
  GradedMeshSpec s;
  s.lx = 0.03;
  s.ly = 0.02;
  s.lz = 0.025;
  s.nx = 16;
  s.ny = 8;
  s.min_cells = 2;
  s.layers_per_level = 1;
  const GradedMesh g(s, 1);
  ASSERT_GE(g.coarsenings(), 2);
  std::vector<Vec3> at(std::size_t(g.nodes()));
  for (std::size_t p = 0; p < g.planes().size(); ++p)
    for (int j = 0; j <= g.cells_y(g.planes()[p].level); ++j)
      for (int i = 0; i <= g.cells_x(g.planes()[p].level); ++i)
        if (const std::int32_t id = g.node(int(p), i, j); id >= 0) at[std::size_t(id)] = g.position(int(p), i, j);
  std::vector<GradedMesh::Parent> w;
  for (int k = 0; k < 500; ++k) {
    const Vec3 p{s.lx * std::fmod(0.37 * k, 1.0), s.ly * std::fmod(0.61 * k + 0.1, 1.0), s.lz * std::fmod(0.23 * k, 1.0)};
    g.interpolation_at(p, w);
    double sum = 0, value = 0;
    for (const auto& q : w) {
      sum += q.weight;
      value += q.weight * linear_field(at[std::size_t(q.id)]);
    }
    EXPECT_NEAR(sum, 1.0, 1e-13);
    EXPECT_NEAR(value, linear_field(p), 1e-13);
  }
}

// A block with frames turned on the face and eliminated dofs (contact normals, the top), as the
// active-set loop leaves it before a solve.
struct FramedBlock {
  GradedMeshSpec spec;
  GradedMesh mesh;
  std::vector<std::int32_t> slot;
  MatrixFreeFramed op;
  explicit FramedBlock(int nx)
      : spec(make_spec(nx)), mesh(spec, ranks()), slot(face_slots(mesh)), op(mesh, PETSC_COMM_WORLD, 3e6, 0.45, slot) {
    const std::size_t slots = std::size_t((nx + 1) * (nx + 1));
    std::vector<double> frames(9 * slots);
    for (std::size_t s = 0; s < slots; ++s) {
      const double a = 0.7 * double(s), t = 0.3 * std::sin(0.05 * double(s));
      const double ca = std::cos(a), sa = std::sin(a), ct = std::cos(t), st = std::sin(t);
      const double q[9] = {ca, -sa * ct, sa * st, sa, ca * ct, -ca * st, 0, st, ct};
      std::copy(q, q + 9, &frames[9 * s]);
    }
    op.set_frames(frames);
  }
  static int ranks() {
    int n = 1;
    MPI_Comm_size(PETSC_COMM_WORLD, &n);
    return n;
  }
  static GradedMeshSpec make_spec(int nx) {
    GradedMeshSpec s;
    s.lx = s.ly = s.lz = 0.02;
    s.nx = s.ny = nx;
    return s;
  }
  static std::vector<std::int32_t> face_slots(const GradedMesh& g) {
    std::vector<std::int32_t> slot(std::size_t(g.nodes()), -1);
    for (int j = 0; j <= g.cells_y(0); ++j)
      for (int i = 0; i <= g.cells_x(0); ++i) slot[std::size_t(g.node(0, i, j))] = j * (g.cells_x(0) + 1) + i;
    return slot;
  }
  // The normal dof of the face nodes in a disc around the centre, and the whole top.
  void eliminate(Vec x, Vec b) {
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    std::vector<PetscInt> rows;
    const int nx = spec.nx, top = mesh.layers(), tl = mesh.planes().back().level;
    for (int j = 0; j <= nx; ++j)
      for (int i = 0; i <= nx; ++i) {
        const std::int32_t id = mesh.node(0, i, j);
        const double r = std::hypot(i - 0.5 * nx, j - 0.5 * nx);
        if (id >= mesh.owned_begin(rank) && id < mesh.owned_end(rank) && r < 0.3 * nx) rows.push_back(3 * PetscInt(id) + 2);
      }
    for (int j = 0; j <= mesh.cells_y(tl); ++j)
      for (int i = 0; i <= mesh.cells_x(tl); ++i) {
        const std::int32_t id = mesh.node(top, i, j);
        if (id >= mesh.owned_begin(rank) && id < mesh.owned_end(rank))
          for (int c = 0; c < 3; ++c) rows.push_back(3 * PetscInt(id) + c);
      }
    op.eliminate(rows, 1e5, x, b, nullptr);
  }
};

Vec random_vector(MPI_Comm comm, Vec like, int seed) {
  Vec v = nullptr;
  VecDuplicate(like, &v);
  PetscRandom rnd = nullptr;
  PetscRandomCreate(comm, &rnd);
  PetscRandomSetSeed(rnd, static_cast<unsigned long>(seed));
  PetscRandomSeed(rnd);
  VecSetRandom(v, rnd);
  PetscRandomDestroy(&rnd);
  return v;
}

// CG needs a symmetric positive definite preconditioner: one V-cycle B satisfies
// <B x, y> = <x, B y> to round-off and <B x, x> > 0, with turned frames and eliminations. With
// the smoothers in double, to 1e-10; in float (the default), to 1e-6: float's unit round-off,
// 6e-8, times the products' cancellation (a stiffness row sums to about zero).
TEST(GeometricMultigrid, VCycleIsSymmetricPositiveDefinite) {
  for (bool single : {false, true}) {
    FramedBlock blk(64);
    Vec x0 = nullptr, b0 = nullptr;
    MatCreateVecs(blk.op.mat(), &x0, &b0);
    VecSet(x0, 0.0);
    blk.eliminate(x0, b0);
    GmgSettings settings = gmg_settings_from_options();
    settings.single = single;
    GeometricMultigrid mg(blk.spec, blk.mesh, blk.op, PETSC_COMM_WORLD, 3e6, 0.45, settings);
    EXPECT_GE(mg.levels(), 3) << mg.describe();
    mg.update();
    Vec x = random_vector(PETSC_COMM_WORLD, x0, 1), y = random_vector(PETSC_COMM_WORLD, x0, 2), bx = nullptr, by = nullptr;
    VecDuplicate(x, &bx);
    VecDuplicate(x, &by);
    mg.apply(x, bx);
    mg.apply(y, by);
    PetscScalar bxy = 0, xby = 0, bxx = 0;
    VecDot(bx, y, &bxy);
    VecDot(x, by, &xby);
    VecDot(bx, x, &bxx);
    EXPECT_NEAR(bxy / xby, 1.0, single ? 1e-6 : 1e-10) << "single " << single;
    EXPECT_GT(bxx, 0.0);
    for (Vec* v : {&x0, &b0, &x, &y, &bx, &by}) VecDestroy(v);
  }
}

// Multigrid's defining property: CG's iterations to a fixed reduction do not grow with the mesh.
// Faces of 16, 32 and 64 cells (3 to 5 levels), the same frames and constraints, rtol 1e-8.
TEST(GeometricMultigrid, IterationsDoNotGrowWithTheMesh) {
  std::vector<PetscInt> its;
  for (int nx : {16, 32, 64}) {
    FramedBlock blk(nx);
    Vec x = nullptr, b = nullptr;
    MatCreateVecs(blk.op.mat(), &x, &b);
    VecSet(x, 0.0);
    blk.eliminate(x, b);
    GeometricMultigrid mg(blk.spec, blk.mesh, blk.op, PETSC_COMM_WORLD, 3e6, 0.45, gmg_settings_from_options());
    mg.update();
    Vec f = random_vector(PETSC_COMM_WORLD, x, 5);
    KSP ksp = nullptr;
    KSPCreate(PETSC_COMM_WORLD, &ksp);
    KSPSetType(ksp, KSPCG);
    KSPSetOperators(ksp, blk.op.mat(), blk.op.mat());
    PC pc = nullptr;
    KSPGetPC(ksp, &pc);
    mg.attach(pc);
    KSPSetTolerances(ksp, 1e-8, 0, PETSC_DEFAULT, 500);
    KSPSolve(ksp, f, x);
    KSPConvergedReason reason;
    KSPGetConvergedReason(ksp, &reason);
    EXPECT_GT(int(reason), 0) << nx;
    PetscInt n = 0;
    KSPGetIterationNumber(ksp, &n);
    its.push_back(n);
    KSPDestroy(&ksp);
    for (Vec* v : {&x, &b, &f}) VecDestroy(v);
  }
  std::printf("CG iterations %d %d %d\n", int(its[0]), int(its[1]), int(its[2]));
  EXPECT_LE(its[2], its[0] + its[0] / 2 + 3) << its[0] << " " << its[1] << " " << its[2];
  EXPECT_LE(its[2], 40);
}

// The same contact states as AMG: the Hertz-like cap (force and contact set to the solver's
// tolerance) and the flat press (uniaxial compression to 1e-8), with no matrix assembled.
TEST(GeometricMultigrid, ReachesTheContactStatesOfAmg) {
  const PeriodicObstacle cap(paraboloid_cap(48, 0.03, 0.05));
  ContactSolution by[2];
  const LinearSolver solvers[2] = {LinearSolver::amg, LinearSolver::gmg};
  for (int k = 0; k < 2; ++k) {
    BlockSpec b;
    b.mesh.nx = b.mesh.ny = 24;
    b.solver = solvers[k];
    ElasticBlock block(b);
    EXPECT_EQ(block.linear_solver(), solvers[k]);
    ContactLoad load;
    load.obstacle = &cap;
    load.uz = 1e-4;
    load.tolerance = 1e-8;
    load.ksp_rtol = 1e-11;
    by[k] = block.solve(load);
    ASSERT_TRUE(by[k].converged) << by[k].message;
  }
  EXPECT_NEAR(by[1].fz / by[0].fz, 1.0, 1e-6);
  EXPECT_EQ(by[1].contact_nodes, by[0].contact_nodes);
  EXPECT_LT(by[1].max_penetration, 1e-7);

  BlockSpec b;
  b.mesh.lx = 0.03;
  b.mesh.ly = 0.02;
  b.mesh.lz = 0.025;
  b.mesh.nx = 16;
  b.mesh.ny = 8;
  b.mesh.min_cells = 2;
  b.young = 3.0e6;
  b.solver = LinearSolver::gmg;
  ElasticBlock block(b);
  EXPECT_THROW(block.assembled_stiffness(), std::logic_error);
  ContactLoad load;
  load.uz = 1e-4;
  load.top = TopCondition::frictionless;
  load.ksp_rtol = 1e-13;
  load.tolerance = 1e-12;
  const ContactSolution s = block.solve(load);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_NEAR(s.fz / (b.young * b.mesh.lx * b.mesh.ly * load.uz / b.mesh.lz), 1.0, 1e-8);
}

}  // namespace
}  // namespace wr
