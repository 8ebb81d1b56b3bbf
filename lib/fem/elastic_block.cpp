#include "lib/fem/elastic_block.hpp"

#include <petscdmda.h>
#include <petscksp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

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
  DM da = nullptr;
  Mat K = nullptr;
  Vec u = nullptr;  // current displacement, carried from load step to load step
  std::vector<double> z;  // node heights, k = 0..nz
  PetscInt xs, ys, zs, xm, ym, zm;
  PetscInt rstart = 0;
  std::vector<char> active;  // per owned bottom node, carried between solves

  PetscInt global_dof(PetscInt i, PetscInt j, PetscInt k, int c) const {
    return rstart + 3 * ((k - zs) * xm * ym + (j - ys) * xm + (i - xs)) + c;
  }
  double hx() const { return spec.lx / spec.nx; }
  double hy() const { return spec.ly / spec.ny; }

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
    // Node coordinates (for output): uniform in x, y, graded in z.
    check(DMDASetUniformCoordinates(da, 0, spec.lx, 0, spec.ly, 0, spec.lz), "DMDASetUniformCoordinates");
    DM cda;
    Vec coords;
    check(DMGetCoordinateDM(da, &cda), "DMGetCoordinateDM");
    check(DMGetCoordinates(da, &coords), "DMGetCoordinates");
    DMDACoor3d*** c;
    check(DMDAVecGetArray(cda, coords, &c), "DMDAVecGetArray");
    for (PetscInt k = zs; k < zs + zm; ++k)
      for (PetscInt j = ys; j < ys + ym; ++j)
        for (PetscInt i = xs; i < xs + xm; ++i) c[k][j][i].z = z[k];
    check(DMDAVecRestoreArray(cda, coords, &c), "DMDAVecRestoreArray");
  }

  void assemble() {
    check(DMCreateMatrix(da, &K), "DMCreateMatrix");
    check(MatSetOption(K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
    std::map<int, ElementMatrix> layer;  // one element matrix per layer thickness
    MatStencil rows[24];
    for (PetscInt k = zs; k < std::min<PetscInt>(zs + zm, spec.nz); ++k) {
      auto it = layer.find(int(k));
      if (it == layer.end())
        it = layer.emplace(int(k), brick_stiffness(hx(), hy(), z[k + 1] - z[k], spec.young, spec.poisson)).first;
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
    check(DMCreateGlobalVector(da, &u), "DMCreateGlobalVector");
    check(VecSet(u, 0.0), "VecSet");
  }
};

ElasticBlock::ElasticBlock(const BlockSpec& spec) : impl_(new Impl) {
  impl_->spec = spec;
  impl_->make_grid();
  impl_->assemble();
}

ElasticBlock::~ElasticBlock() {
  if (impl_->u) VecDestroy(&impl_->u);
  if (impl_->K) MatDestroy(&impl_->K);
  if (impl_->da) DMDestroy(&impl_->da);
  delete impl_;
}

void ElasticBlock::write_vts(const std::string& path) const {
  PetscViewer viewer;
  check(PetscViewerVTKOpen(PETSC_COMM_WORLD, path.c_str(), FILE_MODE_WRITE, &viewer), "PetscViewerVTKOpen");
  check(PetscObjectSetName(reinterpret_cast<PetscObject>(impl_->u), "displacement"), "PetscObjectSetName");
  check(VecView(impl_->u, viewer), "VecView");
  check(PetscViewerDestroy(&viewer), "PetscViewerDestroy");
}

std::size_t ElasticBlock::nodes() const {
  return std::size_t(impl_->spec.nx + 1) * (impl_->spec.ny + 1) * (impl_->spec.nz + 1);
}

namespace {

struct FaceNode {
  PetscInt i, j;
  PetscInt row[3];  // global dofs
  Vec3 x0;          // reference position
  Vec3 normal{0, 0, 1};  // obstacle normal N of the current linearisation
  double g = -INFINITY;  // bound on N . u (-inf: no obstacle within reach)
};

// Block-diagonal rotation: Q(N) on the face nodes, identity elsewhere; same pattern always.
void fill_rotation(Mat R, PetscInt rstart, PetscInt rend, const std::vector<FaceNode>& face) {
  for (PetscInt r = rstart; r < rend; r += 3)
    for (int c = 0; c < 3; ++c) MatSetValue(R, r + c, r + c, 1.0, INSERT_VALUES);
  for (const FaceNode& f : face) {
    const auto q = frame_of(f.normal);
    MatSetValues(R, 3, f.row, 3, f.row, q.data(), INSERT_VALUES);
  }
  MatAssemblyBegin(R, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(R, MAT_FINAL_ASSEMBLY);
}

}  // namespace

ContactSolution ElasticBlock::solve(const ContactLoad& load) {
  Impl& m = *impl_;
  const BlockSpec& s = m.spec;
  ContactSolution out;
  out.face_nodes = std::size_t(s.nx + 1) * (s.ny + 1);
  PetscInt rend;
  check(MatGetOwnershipRange(m.K, nullptr, &rend), "MatGetOwnershipRange");

  std::vector<FaceNode> face;
  if (m.zs == 0)
    for (PetscInt j = m.ys; j < m.ys + m.ym; ++j)
      for (PetscInt i = m.xs; i < m.xs + m.xm; ++i) {
        FaceNode f{i, j, {m.global_dof(i, j, 0, 0), m.global_dof(i, j, 0, 1), m.global_dof(i, j, 0, 2)},
                   Vec3{i * m.hx(), j * m.hy(), 0.0}};
        face.push_back(f);
      }
  if (m.active.size() != face.size()) m.active.assign(face.size(), 0);

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
    if (m.xs == 0 && m.ys == 0) {  // in-plane rigid motion is free: pin it
      fixed_rows.insert(fixed_rows.end(), {m.global_dof(0, 0, 0, 0), m.global_dof(0, 0, 0, 1)});
      fixed_vals.insert(fixed_vals.end(), {0.0, 0.0});
    }
    if (m.xs + m.xm == s.nx + 1 && m.ys == 0) {
      fixed_rows.push_back(m.global_dof(s.nx, 0, 0, 1));
      fixed_vals.push_back(0.0);
    }
  }
  check(VecSetValues(m.u, PetscInt(fixed_rows.size()), fixed_rows.data(), fixed_vals.data(), INSERT_VALUES), "VecSetValues");
  check(VecAssemblyBegin(m.u), "VecAssemblyBegin");
  check(VecAssemblyEnd(m.u), "VecAssemblyEnd");

  Mat R, Khat = nullptr, A = nullptr;
  check(MatCreate(PETSC_COMM_WORLD, &R), "MatCreate");
  check(MatSetSizes(R, rend - m.rstart, rend - m.rstart, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(R, MATAIJ), "MatSetType");
  check(MatSetBlockSize(R, 3), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocation(R, 3, nullptr), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(R, 3, nullptr, 0, nullptr), "MatMPIAIJSetPreallocation");
  Vec uh, b, r, diag, ustar, ulocal;
  check(VecDuplicate(m.u, &uh), "VecDuplicate");
  check(VecDuplicate(m.u, &b), "VecDuplicate");
  check(VecDuplicate(m.u, &r), "VecDuplicate");
  check(VecDuplicate(m.u, &diag), "VecDuplicate");
  check(VecDuplicate(m.u, &ustar), "VecDuplicate");
  check(DMCreateLocalVector(m.da, &ulocal), "DMCreateLocalVector");
  KSP ksp;
  check(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetTolerances(ksp, load.ksp_rtol, 1e-300, PETSC_DEFAULT, 20000), "KSPSetTolerances");
  check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");

  const double reach = std::max(s.lz, 1e-12);  // rays look this far for the obstacle
  const int outer_max = load.follow_geometry ? load.max_outer_iterations : 1;
  double alpha_now = load.damping;
  std::vector<double> normal_force(face.size(), 0.0);  // N, per face node, last linearisation
  int first_its = -1;  // CG iterations with a fresh preconditioner
  std::vector<double> prev_corr(3 * face.size(), 0.0);
  for (int outer = 0; outer < outer_max; ++outer) {
    out.outer_iterations = outer + 1;
    // 1. Linearise the contact at the current configuration.
    check(DMGlobalToLocal(m.da, m.u, INSERT_VALUES, ulocal), "DMGlobalToLocal");
    PetscScalar**** ul;
    check(DMDAVecGetArrayDOFRead(m.da, ulocal, &ul), "DMDAVecGetArrayDOFRead");
    PetscInt gxs, gys, gzs, gxm, gym, gzm;
    DMDAGetGhostCorners(m.da, &gxs, &gys, &gzs, &gxm, &gym, &gzm);
    auto X = [&](PetscInt i, PetscInt j) {
      i = std::clamp(i, gxs, gxs + gxm - 1);
      j = std::clamp(j, gys, gys + gym - 1);
      return Vec3{i * m.hx() + ul[0][j][i][0], j * m.hy() + ul[0][j][i][1], ul[0][j][i][2]};
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
      const Vec3 t1 = X(std::min<PetscInt>(f.i + 1, s.nx), f.j) - X(std::max<PetscInt>(f.i - 1, 0), f.j);
      const Vec3 t2 = X(f.i, std::min<PetscInt>(f.j + 1, s.ny)) - X(f.i, std::max<PetscInt>(f.j - 1, 0));
      const Vec3 n = t2.cross(t1).unit();
      const auto hit = load.obstacle->cast(here, n, reach);
      if (!hit) {
        f.normal = {0, 0, 1};
        f.g = -INFINITY;
        continue;
      }
      f.normal = hit->normal;
      f.g = hit->normal.dot(hit->point - f.x0);  // N . (x0 + u) >= N . q
    }
    DMDAVecRestoreArrayDOFRead(m.da, ulocal, &ul);

    // 2. Rotate the face nodes into their constraint frames: Khat = R^T K R, uh = R^T u.
    check(MatZeroEntries(R), "MatZeroEntries");
    fill_rotation(R, m.rstart, rend, face);
    check(MatPtAP(m.K, R, Khat ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, 2.0, &Khat), "MatPtAP");
    check(MatSetBlockSize(Khat, 3), "MatSetBlockSize");
    if (!A) check(MatDuplicate(Khat, MAT_COPY_VALUES, &A), "MatDuplicate");
    check(MatGetDiagonal(Khat, diag), "MatGetDiagonal");
    // Eliminated rows get a diagonal of the matrix's own scale, so that AMG smoothers see no
    // stray unit entries among stiffnesses of order E h.
    PetscScalar diag_sum;
    PetscInt diag_n;
    VecSum(diag, &diag_sum);
    VecGetSize(diag, &diag_n);
    const double unit_diag = diag_sum / double(diag_n);
    check(MatMultTranspose(R, m.u, uh), "MatMultTranspose");

    // 3. Primal-dual active set on the bounds uh_z >= g at the face nodes.
    bool pdas_ok = false;
    std::size_t contact = 0;
    {
      const PetscScalar* a;
      VecGetArrayRead(uh, &a);
      for (std::size_t n = 0; n < face.size(); ++n)
        if (std::isfinite(face[n].g) && a[face[n].row[2] - m.rstart] <= face[n].g) m.active[n] = 1;
        else if (!std::isfinite(face[n].g)) m.active[n] = 0;
      VecRestoreArrayRead(uh, &a);
    }
    for (int it = 0; it < load.max_active_set_iterations; ++it) {
      ++out.active_set_iterations;
      std::vector<PetscInt> rows = fixed_rows;
      std::vector<double> vals = fixed_vals;
      for (std::size_t n = 0; n < face.size(); ++n)
        if (m.active[n]) {
          rows.push_back(face[n].row[2]);
          vals.push_back(face[n].g);
        }
      check(VecSetValues(uh, PetscInt(rows.size()), rows.data(), vals.data(), INSERT_VALUES), "VecSetValues");
      check(VecAssemblyBegin(uh), "VecAssemblyBegin");
      check(VecAssemblyEnd(uh), "VecAssemblyEnd");
      check(MatCopy(Khat, A, SAME_NONZERO_PATTERN), "MatCopy");
      check(VecSet(b, 0.0), "VecSet");
      check(MatZeroRowsColumns(A, PetscInt(rows.size()), rows.data(), unit_diag, uh, b), "MatZeroRowsColumns");
      check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
      check(KSPSolve(ksp, b, uh), "KSPSolve");
      KSPConvergedReason reason;
      PetscInt its;
      KSPGetConvergedReason(ksp, &reason);
      KSPGetIterationNumber(ksp, &its);
      out.linear_iterations += int(its);
      // Keep the AMG hierarchy of the first system for the later ones of this load step (the
      // systems differ only by rotations and eliminated rows); rebuild it when CG slows down.
      if (load.reuse_preconditioner) {
        if (first_its < 0) first_its = int(its);
        const bool slow = first_its >= 0 && its > 3 * std::max(first_its, 10);
        check(KSPSetReusePreconditioner(ksp, slow ? PETSC_FALSE : PETSC_TRUE), "KSPSetReusePreconditioner");
        if (slow) first_its = -1;
      }
      if (reason < 0) {
        out.message = "linear solve failed (KSP reason " + std::to_string(int(reason)) + ") in Signorini iteration " +
                      std::to_string(outer + 1);
        break;
      }
      check(MatMult(Khat, uh, r), "MatMult");  // reactions in the rotated frames
      const PetscScalar *ra, *ua, *da;
      VecGetArrayRead(r, &ra);
      VecGetArrayRead(uh, &ua);
      VecGetArrayRead(diag, &da);
      int changed = 0;
      contact = 0;
      for (std::size_t n = 0; n < face.size(); ++n) {
        if (!std::isfinite(face[n].g)) continue;
        const PetscInt l = face[n].row[2] - m.rstart;
        const bool now = ra[l] + da[l] * (face[n].g - ua[l]) > 0;
        changed |= now != bool(m.active[n]);
        m.active[n] = now;
        contact += now;
      }
      VecRestoreArrayRead(r, &ra);
      VecRestoreArrayRead(uh, &ua);
      VecRestoreArrayRead(diag, &da);
      int any = 0;
      MPI_Allreduce(&changed, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
      if (!any) {
        pdas_ok = true;
        break;
      }
    }
    if (!pdas_ok) {
      if (out.message.empty())
        out.message = "active set still changing after " + std::to_string(load.max_active_set_iterations) +
                      " iterations in Signorini iteration " + std::to_string(outer + 1);
      break;
    }
    double ct = double(contact), ctot;
    MPI_Allreduce(&ct, &ctot, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    out.contact_nodes = std::size_t(ctot);
    {
      const PetscScalar* ra;
      VecGetArrayRead(r, &ra);
      for (std::size_t n = 0; n < face.size(); ++n)
        normal_force[n] = m.active[n] ? ra[face[n].row[2] - m.rstart] : 0.0;
      VecRestoreArrayRead(r, &ra);
    }

    // 4. Damped correction and its size on the contact face.
    check(MatMult(R, uh, ustar), "MatMult");
    const PetscScalar* us;
    PetscScalar* uc;
    VecGetArrayRead(ustar, &us);
    VecGetArray(m.u, &uc);
    // Damping: halved when the correction reverses (a node chattering between two contact
    // states across a kink of the obstacle), restored while corrections keep their direction.
    double cc = 0, cp = 0, pp = 0;
    for (std::size_t n = 0; n < face.size(); ++n)
      for (int c = 0; c < 3; ++c) {
        const PetscInt l = face[n].row[c] - m.rstart;
        const double corr = us[l] - uc[l];
        cc += corr * corr;
        cp += corr * prev_corr[3 * n + c];
        pp += prev_corr[3 * n + c] * prev_corr[3 * n + c];
        prev_corr[3 * n + c] = corr;
      }
    double dots[3] = {cc, cp, pp}, gdots[3];
    MPI_Allreduce(dots, gdots, 3, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    if (load.follow_geometry && gdots[2] > 0) {
      const double cosine = gdots[1] / std::sqrt(gdots[0] * gdots[2]);
      if (cosine < -0.3)
        alpha_now = std::max(0.5 * alpha_now, 0.01);
      else if (cosine > 0.7)
        alpha_now = std::min(1.5 * alpha_now, load.damping);
    }
    const double alpha = load.follow_geometry ? alpha_now : 1.0;
    double dc = 0, du = 0;
    for (const FaceNode& f : face)
      for (int c = 0; c < 3; ++c) {
        const PetscInt l = f.row[c] - m.rstart;
        const double corr = us[l] - uc[l];
        dc += corr * corr;
        du += (uc[l] + alpha * corr) * (uc[l] + alpha * corr);
      }
    PetscInt n_local;
    VecGetLocalSize(m.u, &n_local);
    for (PetscInt l = 0; l < n_local; ++l) uc[l] += alpha * (us[l] - uc[l]);
    VecRestoreArrayRead(ustar, &us);
    VecRestoreArray(m.u, &uc);
    double loc[2] = {dc, du}, glob[2];
    MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    // Relative size of the step actually taken on the contact face.
    const double change = glob[1] > 0 ? alpha * std::sqrt(glob[0] / glob[1]) : 0.0;
    out.history.push_back(change);
    out.final_damping = alpha;
    if (!load.follow_geometry || change <= load.tolerance) {
      check(VecCopy(ustar, m.u), "VecCopy");  // the undamped solution of the last linearisation
      out.converged = true;
      break;
    }
  }
  if (!out.converged && out.message.empty())
    out.message = "Signorini iteration did not converge in " + std::to_string(load.max_outer_iterations) +
                  " iterations (last relative change " + (out.history.empty() ? "-" : std::to_string(out.history.back())) + ")";

  // Reactions on the top face, separation and penetration of the face.
  check(MatMult(m.K, m.u, r), "MatMult");
  const PetscScalar *rr, *uu;
  VecGetArrayRead(r, &rr);
  VecGetArrayRead(m.u, &uu);
  double fz = 0, fx = 0, fy = 0, sep = 0, pen = 0;
  for (PetscInt row : top_rows[0]) fx += rr[row - m.rstart];
  for (PetscInt row : top_rows[1]) fy += rr[row - m.rstart];
  for (PetscInt row : top_rows[2]) fz -= rr[row - m.rstart];
  for (const FaceNode& f : face) {
    const Vec3 p{f.x0.x + uu[f.row[0] - m.rstart], f.x0.y + uu[f.row[1] - m.rstart], uu[f.row[2] - m.rstart]};
    const double h = load.obstacle ? load.obstacle->height(p.x, p.y) : 0.0;
    sep += std::max(0.0, p.z - h);
    pen = std::max(pen, h - p.z);
  }
  if (load.face_maps) {
    const std::size_t nfx = std::size_t(s.nx + 1), nf = nfx * std::size_t(s.ny + 1);
    std::vector<double> local(3 * nf, 0.0);
    for (std::size_t n = 0; n < face.size(); ++n) {
      const FaceNode& f = face[n];
      const std::size_t idx = std::size_t(f.j) * nfx + std::size_t(f.i);
      // Nodal area: a quarter cell per adjacent cell.
      const double wx = (f.i == 0 || f.i == s.nx) ? 0.5 : 1.0, wy = (f.j == 0 || f.j == s.ny) ? 0.5 : 1.0;
      local[idx] = normal_force[n] / (wx * wy * m.hx() * m.hy());
      const Vec3 p{f.x0.x + uu[f.row[0] - m.rstart], f.x0.y + uu[f.row[1] - m.rstart], uu[f.row[2] - m.rstart]};
      local[nf + idx] = p.z - (load.obstacle ? load.obstacle->height(p.x, p.y) : 0.0);
      local[2 * nf + idx] = m.active[n] ? 1.0 : 0.0;
    }
    std::vector<double> global(3 * nf, 0.0);
    MPI_Reduce(local.data(), global.data(), int(3 * nf), MPI_DOUBLE, MPI_SUM, 0, PETSC_COMM_WORLD);
    out.face_pressure.assign(global.begin(), global.begin() + nf);
    out.face_gap.assign(global.begin() + nf, global.begin() + 2 * nf);
    out.face_status.assign(global.begin() + 2 * nf, global.end());
  }
  VecRestoreArrayRead(r, &rr);
  VecRestoreArrayRead(m.u, &uu);
  double loc[5] = {fx, fy, fz, sep, 0}, glob[5];
  MPI_Allreduce(loc, glob, 5, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(&pen, &out.max_penetration, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  out.fx = glob[0];
  out.fy = glob[1];
  out.fz = glob[2];
  out.mean_separation = glob[3] / double(out.face_nodes);

  KSPDestroy(&ksp);
  if (A) MatDestroy(&A);
  if (Khat) MatDestroy(&Khat);
  MatDestroy(&R);
  VecDestroy(&uh);
  VecDestroy(&b);
  VecDestroy(&r);
  VecDestroy(&diag);
  VecDestroy(&ustar);
  VecDestroy(&ulocal);
  return out;
}

}  // namespace wr
