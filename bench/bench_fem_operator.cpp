#include "bench/bench_fem_operator.hpp"

#include <petscmat.h>

#include <algorithm>
#include <cstdio>

#include "bench/bench_common.hpp"
#include "lib/core/provenance.hpp"
#include "lib/fem/elastic_block.hpp"
#include "lib/fem/matrix_free_stiffness.hpp"

namespace wr::bench {
namespace {

// Best wall time of `repeats` products y = A x, every rank waiting for the slowest.
double best_product(Mat a, Vec x, Vec y, int repeats) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    MPI_Barrier(PETSC_COMM_WORLD);
    const double t0 = now();
    MatMult(a, x, y);
    MPI_Barrier(PETSC_COMM_WORLD);
    best = std::min(best, now() - t0);
  }
  return best;
}

double sum_over_ranks(double v) {
  double s = 0;
  MPI_Allreduce(&v, &s, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return s;
}

}  // namespace

nlohmann::json fem_operator(int size, const std::vector<int>& refines, int repeats) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  nlohmann::json rows = nlohmann::json::array();
  for (int refine : refines) {
    BlockSpec b;
    b.mesh.lx = b.mesh.ly = b.mesh.lz = 0.03;
    b.mesh.nx = b.mesh.ny = size * refine;
    b.young = 1e7;
    b.poisson = 0.45;
    b.solver = LinearSolver::amg;  // the assembled matrix is the comparison
    const double t0 = now();
    ElasticBlock block(b);
    const double t_assembled = now() - t0;
    const double t1 = now();
    const MatrixFreeStiffness mf(block.mesh(), block.comm(), b.young, b.poisson);
    const double t_setup = now() - t1;
    Mat k = block.assembled_stiffness();
    Vec x = nullptr, ya = nullptr, ym = nullptr;
    MatCreateVecs(k, &x, &ya);
    VecDuplicate(ya, &ym);
    PetscRandom rnd = nullptr;
    PetscRandomCreate(PETSC_COMM_WORLD, &rnd);
    PetscRandomSetSeed(rnd, 11);
    PetscRandomSeed(rnd);
    VecSetRandom(x, rnd);
    const double t_aij = best_product(k, x, ya, repeats);
    const double t_mf = best_product(mf.mat(), x, ym, repeats);
    PetscReal scale = 0, diff = 0;
    VecNorm(ya, NORM_INFINITY, &scale);
    VecAXPY(ym, -1.0, ya);
    VecNorm(ym, NORM_INFINITY, &diff);
    MatInfo info;
    MatGetInfo(k, MAT_GLOBAL_SUM, &info);
    PetscInt dofs = 0;
    VecGetSize(x, &dofs);
    const double mf_bytes = sum_over_ranks(double(mf.memory_bytes()));
    nlohmann::json row = {{"refine", refine},
                          {"ranks", ranks},
                          {"nodes", double(block.mesh().nodes())},
                          {"dofs", double(dofs)},
                          {"relative_difference", diff / scale},
                          {"aij_product_s", t_aij},
                          {"matrix_free_product_s", t_mf},
                          {"speedup", t_aij / t_mf},
                          // CSR: a value and a column index per nonzero, a row start per row
                          {"aij_bytes", info.nz_used * (sizeof(PetscScalar) + sizeof(PetscInt)) + double(dofs) * sizeof(PetscInt)},
                          {"aij_nonzeros", info.nz_used},
                          {"matrix_free_bytes", mf_bytes},
                          {"stencil_classes_rank0", double(mf.stencils().classes())},
                          {"stencil_runs_rank0", double(mf.stencils().runs())},
                          {"assembly_s", t_assembled},
                          {"matrix_free_setup_s", t_setup},
                          {"peak_rss_bytes_rank0", double(peak_rss_bytes())}};
    if (rank == 0)
      std::fprintf(stderr, "  refine %d: %.0f dofs, AIJ %.4f s, matrix-free %.4f s per product, difference %.1e\n", refine,
                   double(dofs), t_aij, t_mf, diff / scale);
    rows.push_back(row);
    PetscRandomDestroy(&rnd);
    VecDestroy(&x);
    VecDestroy(&ya);
    VecDestroy(&ym);
  }
  return {{"size", size}, {"repeats", repeats}, {"rows", rows}};
}

}  // namespace wr::bench
