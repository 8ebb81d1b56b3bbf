#include "lib/fem/elastic_block.hpp"

#include <petscdmda.h>
#include <petscksp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace wr {
namespace {

// PETSc calls return error codes; turn them into exceptions with the call's name.
void check(PetscErrorCode ierr, const char* what) {
  if (ierr) throw std::runtime_error(std::string("PETSc failed in ") + what + " (code " + std::to_string(ierr) + ")");
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

}  // namespace

struct ElasticBlock::Impl {
  BlockSpec spec;
  DM da = nullptr;
  Mat K = nullptr;
  std::vector<double> z;  // node heights, k = 0..nz
  PetscInt xs, ys, zs, xm, ym, zm;
  PetscInt rstart = 0;

  PetscInt global_dof(PetscInt i, PetscInt j, PetscInt k, int c) const {
    return rstart + 3 * ((k - zs) * xm * ym + (j - ys) * xm + (i - xs)) + c;
  }

  void make_grid() {
    const PetscInt M = spec.nx + 1, N = spec.ny + 1, P = spec.nz + 1;
    check(DMDACreate3d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX, M, N,
                       P, PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, 3, 1, nullptr, nullptr, nullptr, &da),
          "DMDACreate3d");
    check(DMSetFromOptions(da), "DMSetFromOptions");
    check(DMSetUp(da), "DMSetUp");
    check(DMDAGetCorners(da, &xs, &ys, &zs, &xm, &ym, &zm), "DMDAGetCorners");
    z.resize(spec.nz + 1);
    for (int k = 0; k <= spec.nz; ++k) z[k] = spec.lz * std::pow(double(k) / spec.nz, spec.grading);
  }

  void assemble() {
    check(DMCreateMatrix(da, &K), "DMCreateMatrix");
    check(MatSetOption(K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
    const double hx = spec.lx / spec.nx, hy = spec.ly / spec.ny;
    std::map<int, ElementMatrix> layer;  // one element matrix per layer thickness
    MatStencil rows[24];
    for (PetscInt k = zs; k < std::min<PetscInt>(zs + zm, spec.nz); ++k) {
      auto it = layer.find(int(k));
      if (it == layer.end())
        it = layer.emplace(int(k), brick_stiffness(hx, hy, z[k + 1] - z[k], spec.young, spec.poisson)).first;
      for (PetscInt j = ys; j < std::min<PetscInt>(ys + ym, spec.ny); ++j)
        for (PetscInt i = xs; i < std::min<PetscInt>(xs + xm, spec.nx); ++i) {
          for (int a = 0; a < 8; ++a)
            for (int c = 0; c < 3; ++c) {
              MatStencil& s = rows[a * 3 + c];
              s.i = i + (a & 1);
              s.j = j + ((a >> 1) & 1);
              s.k = k + ((a >> 2) & 1);
              s.c = c;
            }
          check(MatSetValuesStencil(K, 24, rows, 24, rows, it->second.data(), ADD_VALUES), "MatSetValuesStencil");
        }
    }
    check(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(MatGetOwnershipRange(K, &rstart, nullptr), "MatGetOwnershipRange");
  }
};

ElasticBlock::ElasticBlock(const BlockSpec& spec) : impl_(new Impl) {
  impl_->spec = spec;
  impl_->make_grid();
  impl_->assemble();
}

ElasticBlock::~ElasticBlock() {
  if (impl_->K) MatDestroy(&impl_->K);
  if (impl_->da) DMDestroy(&impl_->da);
  delete impl_;
}

std::size_t ElasticBlock::nodes() const {
  return std::size_t(impl_->spec.nx + 1) * (impl_->spec.ny + 1) * (impl_->spec.nz + 1);
}

ContactSolution ElasticBlock::solve(const ContactLoad& load) {
  Impl& m = *impl_;
  const BlockSpec& s = m.spec;
  const double hx = s.lx / s.nx, hy = s.ly / s.ny;
  ContactSolution out;
  out.face_nodes = std::size_t(s.nx + 1) * (s.ny + 1);

  // Gap of every owned bottom node: u_z >= g = obstacle - max(obstacle).
  struct BottomNode {
    PetscInt row;  // global z dof
    double g;
  };
  std::vector<BottomNode> bottom;
  double local_max = -INFINITY;
  if (m.zs == 0)
    for (PetscInt j = m.ys; j < m.ys + m.ym; ++j)
      for (PetscInt i = m.xs; i < m.xs + m.xm; ++i) {
        const double h = load.obstacle ? load.obstacle(i * hx, j * hy) : 0.0;
        bottom.push_back({m.global_dof(i, j, 0, 2), h});
        local_max = std::max(local_max, h);
      }
  double hmax = 0;
  MPI_Allreduce(&local_max, &hmax, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  for (auto& b : bottom) b.g -= hmax;

  // Prescribed top dofs and the minimal pins of a frictionless top.
  std::vector<PetscInt> fixed_rows;
  std::vector<double> fixed_vals;
  std::vector<PetscInt> top_rows[3];
  if (m.zs + m.zm == s.nz + 1)
    for (PetscInt j = m.ys; j < m.ys + m.ym; ++j)
      for (PetscInt i = m.xs; i < m.xs + m.xm; ++i)
        for (int c = 0; c < 3; ++c) {
          top_rows[c].push_back(m.global_dof(i, j, s.nz, c));
          if (load.top == TopCondition::frictionless && c < 2) continue;
          fixed_rows.push_back(m.global_dof(i, j, s.nz, c));
          fixed_vals.push_back(c == 0 ? load.ux : (c == 1 ? 0.0 : -load.uz));
        }
  if (load.top == TopCondition::frictionless && m.zs == 0) {
    // Rigid in-plane motion is free: pin u_x, u_y at (0,0,0) and u_y at (nx,0,0).
    if (m.xs == 0 && m.ys == 0) {
      fixed_rows.insert(fixed_rows.end(), {m.global_dof(0, 0, 0, 0), m.global_dof(0, 0, 0, 1)});
      fixed_vals.insert(fixed_vals.end(), {0.0, 0.0});
    }
    if (m.xs + m.xm == s.nx + 1 && m.ys == 0) {
      fixed_rows.push_back(m.global_dof(s.nx, 0, 0, 1));
      fixed_vals.push_back(0.0);
    }
  }

  Vec u, b, r;
  check(DMCreateGlobalVector(m.da, &u), "DMCreateGlobalVector");
  check(VecDuplicate(u, &b), "VecDuplicate");
  check(VecDuplicate(u, &r), "VecDuplicate");
  Mat A;
  check(MatDuplicate(m.K, MAT_COPY_VALUES, &A), "MatDuplicate");
  KSP ksp;
  check(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetTolerances(ksp, load.ksp_rtol, 1e-300, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");

  // Diagonal scale for the active-set test R + c (g - u) > 0.
  Vec diag;
  check(VecDuplicate(u, &diag), "VecDuplicate");
  check(MatGetDiagonal(m.K, diag), "MatGetDiagonal");

  std::vector<char> active(bottom.size(), 0);
  for (std::size_t n = 0; n < bottom.size(); ++n) active[n] = bottom[n].g >= 0;  // the touching point(s)
  for (int it = 0; it < load.max_active_set_iterations; ++it) {
    out.active_set_iterations = it + 1;
    // Elimination: prescribed values into u, rows and columns of A zeroed with unit diagonal.
    std::vector<PetscInt> rows = fixed_rows;
    std::vector<double> vals = fixed_vals;
    for (std::size_t n = 0; n < bottom.size(); ++n)
      if (active[n]) {
        rows.push_back(bottom[n].row);
        vals.push_back(bottom[n].g);
      }
    check(VecSetValues(u, PetscInt(rows.size()), rows.data(), vals.data(), INSERT_VALUES), "VecSetValues");
    check(VecAssemblyBegin(u), "VecAssemblyBegin");
    check(VecAssemblyEnd(u), "VecAssemblyEnd");
    check(MatCopy(m.K, A, SAME_NONZERO_PATTERN), "MatCopy");
    check(VecSet(b, 0.0), "VecSet");
    check(MatZeroRowsColumns(A, PetscInt(rows.size()), rows.data(), 1.0, u, b), "MatZeroRowsColumns");
    check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
    check(KSPSolve(ksp, b, u), "KSPSolve");
    KSPConvergedReason reason;
    check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    PetscInt its;
    check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
    out.linear_iterations += int(its);
    if (reason < 0) {
      out.message = "linear solve failed (KSP reason " + std::to_string(int(reason)) + ")";
      break;
    }
    // Reactions R = K u (no body forces) and the new active set.
    check(MatMult(m.K, u, r), "MatMult");
    const PetscScalar *ru, *rr, *rd;
    check(VecGetArrayRead(u, &ru), "VecGetArrayRead");
    check(VecGetArrayRead(r, &rr), "VecGetArrayRead");
    check(VecGetArrayRead(diag, &rd), "VecGetArrayRead");
    int changed = 0;
    double pen = 0;
    std::size_t contact = 0;
    for (std::size_t n = 0; n < bottom.size(); ++n) {
      const PetscInt l = bottom[n].row - m.rstart;
      const bool now = rr[l] + rd[l] * (bottom[n].g - ru[l]) > 0;
      changed |= now != bool(active[n]);
      active[n] = now;
      contact += now;
      pen = std::max(pen, bottom[n].g - ru[l]);
    }
    double fz = 0, fx = 0, fy = 0;
    for (PetscInt row : top_rows[0]) fx += rr[row - m.rstart];
    for (PetscInt row : top_rows[1]) fy += rr[row - m.rstart];
    for (PetscInt row : top_rows[2]) fz -= rr[row - m.rstart];
    VecRestoreArrayRead(u, &ru);
    VecRestoreArrayRead(r, &rr);
    VecRestoreArrayRead(diag, &rd);
    double local[4] = {fx, fy, fz, double(contact)}, global[4];
    MPI_Allreduce(local, global, 4, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    int any_changed = 0;
    MPI_Allreduce(&changed, &any_changed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    MPI_Allreduce(&pen, &out.max_penetration, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    out.fx = global[0];
    out.fy = global[1];
    out.fz = global[2];
    out.contact_nodes = std::size_t(global[3]);
    if (!any_changed) {
      out.converged = true;
      break;
    }
  }
  if (!out.converged && out.message.empty())
    out.message = "active set still changing after " + std::to_string(load.max_active_set_iterations) + " iterations";
  KSPDestroy(&ksp);
  MatDestroy(&A);
  VecDestroy(&diag);
  VecDestroy(&u);
  VecDestroy(&b);
  VecDestroy(&r);
  return out;
}

}  // namespace wr
