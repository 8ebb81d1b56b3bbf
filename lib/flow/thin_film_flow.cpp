#include "lib/flow/thin_film_flow.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "lib/core/errors.hpp"
#include "lib/flow/flow_solvers.hpp"
#include "lib/flow/free_clusters.hpp"

namespace wr {

FlowSolver parse_flow_solver(const std::string& text, const std::string& option) {
  if (text == "auto") return FlowSolver::automatic;
  if (text == "cholmod") return FlowSolver::cholmod;
  if (text == "amg") return FlowSolver::amg;
  throw InputError(option, "must be auto, cholmod or amg, not \"" + text + "\"");
}

const char* flow_solver_name(FlowSolver s) {
  switch (s) {
    case FlowSolver::cholmod: return "cholmod";
    case FlowSolver::amg: return "amg";
    default: return "auto";
  }
}

namespace {

constexpr std::int32_t kInactive = -1;  // contact cell, or a cluster that winds nowhere: no unknown
constexpr std::int32_t kPinned = -2;    // p~ = 0: the one fixed value of its cluster

void check_gap_map(const HeightMap& gap) {
  if (gap.nx == 0 || gap.ny == 0 || gap.h.size() != gap.nx * gap.ny) throw InputError("gap", "the map is empty");
  if (!gap.periodic) throw InputError("gap", "the map is not periodic: the flow model repeats it on a torus");
  if (!(gap.dx > 0 && gap.dy > 0 && std::isfinite(gap.dx) && std::isfinite(gap.dy)))
    throw InputError("gap", "the grid spacings must be finite and > 0");
  for (std::size_t k = 0; k < gap.size(); ++k)
    if (!(gap.h[k] >= 0) || !std::isfinite(gap.h[k]))
      throw InputError("gap", "the gap at (" + std::to_string(k % gap.nx) + ", " + std::to_string(k / gap.nx) + ") is " +
                                  std::to_string(gap.h[k]) + ": it must be finite and >= 0 m");
}

// The face between two cells: the harmonic mean of their g^3/12 (series resistances; 0 when
// either is closed), times the face's length over the distance between the centres.
double face_transmissibility(double c1, double c2, double length_over_distance) {
  if (!(c1 > 0 && c2 > 0)) return 0;
  return 2 * c1 * c2 / (c1 + c2) * length_over_distance;
}

// The linear system of the two solves: per cell its unknown (or kInactive / kPinned), the
// cells' scaled conductances g^3/12 / c_max, and the matrix with the right-hand sides of
// G = e_x (column 0) and G = e_y (column 1).
struct ReynoldsSystem {
  std::vector<std::int32_t> unknown;
  std::vector<double> c;
  double c_max = 0;
  Eigen::SparseMatrix<double> a;
  Eigen::MatrixXd b;
};

// Numbers the cells of the clusters that wind; the first cell of each (row-major) is pinned.
std::size_t number_unknowns(const FreeClusters& fc, std::vector<std::int32_t>& unknown) {
  unknown.assign(fc.label.size(), kInactive);
  std::vector<bool> pinned(fc.winds_x.size(), false);
  std::int32_t next = 0;
  for (std::size_t k = 0; k < fc.label.size(); ++k) {
    const std::int32_t l = fc.label[k];
    if (l < 0 || !(fc.winds_x[std::size_t(l)] || fc.winds_y[std::size_t(l)])) continue;
    if (!pinned[std::size_t(l)]) {
      pinned[std::size_t(l)] = true;
      unknown[k] = kPinned;
    } else {
      unknown[k] = next++;
    }
  }
  return std::size_t(next);
}

// The east and north neighbours of cell k (periodic).
std::size_t east_of(std::size_t k, std::size_t nx) { return k % nx + 1 == nx ? k + 1 - nx : k + 1; }
std::size_t north_of(std::size_t k, std::size_t nx, std::size_t n) { return k + nx >= n ? k + nx - n : k + nx; }

// Finite-volume balance of every active cell: sum over faces T (p~_c - p~_n) = G-terms. For
// G = e_x the face east of c carries T (dx - (p~_e - p~_c)): -T dx enters c's row, +T dx e's.
ReynoldsSystem assemble(const HeightMap& gap, const FreeClusters& fc) {
  ReynoldsSystem s;
  const std::size_t n = gap.size(), nx = gap.nx;
  const std::size_t m = number_unknowns(fc, s.unknown);
  s.c.resize(n);
  for (std::size_t k = 0; k < n; ++k) s.c_max = std::max(s.c_max, gap.h[k] * gap.h[k] * gap.h[k] / 12);
  // Scaled to O(1): conductances span many decades (g^3), and the iterative solver's tolerances
  // and PETSc's zero-pivot tests are absolute somewhere.
  for (std::size_t k = 0; k < n; ++k) s.c[k] = s.c_max > 0 ? gap.h[k] * gap.h[k] * gap.h[k] / 12 / s.c_max : 0;
  s.b = Eigen::MatrixXd::Zero(Eigen::Index(m), 2);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(5 * m);
  auto add_face = [&](std::size_t c, std::size_t o, double tr, int column, double spacing) {
    if (tr == 0 || c == o) return;  // a one-cell period: the face joins the cell to itself
    const std::int32_t uc = s.unknown[c], uo = s.unknown[o];
    if (uc >= 0) t.emplace_back(uc, uc, tr);
    if (uo >= 0) t.emplace_back(uo, uo, tr);
    if (uc >= 0 && uo >= 0) {
      t.emplace_back(uc, uo, -tr);
      t.emplace_back(uo, uc, -tr);
    }
    if (uc >= 0) s.b(uc, column) -= tr * spacing;
    if (uo >= 0) s.b(uo, column) += tr * spacing;
  };
  for (std::size_t k = 0; k < n; ++k) {
    if (s.unknown[k] == kInactive) continue;
    const std::size_t e = east_of(k, nx), no = north_of(k, nx, n);
    add_face(k, e, face_transmissibility(s.c[k], s.c[e], gap.dy / gap.dx), 0, gap.dx);
    add_face(k, no, face_transmissibility(s.c[k], s.c[no], gap.dx / gap.dy), 1, gap.dy);
  }
  s.a.resize(Eigen::Index(m), Eigen::Index(m));
  s.a.setFromTriplets(t.begin(), t.end());
  return s;
}

// p~ of cell k in solve `column` (0 at the pinned cell; never read for inactive cells).
double ptilde(const ReynoldsSystem& s, const Eigen::MatrixXd& x, std::size_t k, int column) {
  const std::int32_t u = s.unknown[k];
  return u >= 0 ? x(u, column) : 0.0;
}

// The face fluxes (eta = 1, |G| = 1), scaled back by c_max: K_{i,j} = mean over the faces normal
// to i of their flux per unit width, in the solve G = e_j; and the field of the solve G = e_x.
void conductance_and_field(const HeightMap& gap, const ReynoldsSystem& s, const Eigen::MatrixXd& x, FlowConductance& r,
                           FlowField* field) {
  const std::size_t n = gap.size(), nx = gap.nx;
  double k[2][2] = {{0, 0}, {0, 0}};  // k[face direction][solve]
  if (field) {
    field->pressure.assign(n, std::numeric_limits<double>::quiet_NaN());
    field->flux_x.assign(n, 0.0);
    field->flux_y.assign(n, 0.0);
  }
  for (std::size_t c = 0; c < n; ++c) {
    if (s.unknown[c] == kInactive) continue;
    const std::size_t e = east_of(c, nx), no = north_of(c, nx, n);
    const double tx = face_transmissibility(s.c[c], s.c[e], gap.dy / gap.dx);
    const double ty = face_transmissibility(s.c[c], s.c[no], gap.dx / gap.dy);
    double fx[2], fy[2];  // face fluxes (times eta), solve by solve
    for (int j = 0; j < 2; ++j) {
      fx[j] = tx * ((j == 0 ? gap.dx : 0.0) - (ptilde(s, x, e, j) - ptilde(s, x, c, j)));
      fy[j] = ty * ((j == 1 ? gap.dy : 0.0) - (ptilde(s, x, no, j) - ptilde(s, x, c, j)));
      k[0][j] += fx[j] * gap.dx;
      k[1][j] += fy[j] * gap.dy;
    }
    if (field) {
      // Per unit width: a face's flux over its length; each face feeds the two cells it bounds.
      const double qx = fx[0] / gap.dy * s.c_max / 2, qy = fy[0] / gap.dx * s.c_max / 2;
      field->flux_x[c] += qx;
      field->flux_x[e] += qx;
      field->flux_y[c] += qy;
      field->flux_y[no] += qy;
      field->pressure[c] = -double(c % nx) * gap.dx + ptilde(s, x, c, 0);
    }
  }
  const double scale = s.c_max / (gap.lx() * gap.ly());
  r.kxx = r.percolates_x ? k[0][0] * scale : 0;
  r.kyy = r.percolates_y ? k[1][1] * scale : 0;
  // Flux in x under a gradient in y exists only if the free area winds in both directions.
  r.kxy = r.percolates_x && r.percolates_y ? k[0][1] * scale : 0;
  r.kyx = r.percolates_x && r.percolates_y ? k[1][0] * scale : 0;
}

FlowSolver resolve(FlowSolver s) { return s == FlowSolver::automatic ? FlowSolver::cholmod : s; }

}  // namespace

Percolation free_area_percolation(const HeightMap& gap) {
  check_gap_map(gap);
  const FreeClusters fc = label_free_clusters(gap);
  return {fc.any_x(), fc.any_y()};
}

FlowConductance thin_film_conductance(const HeightMap& gap, const FlowOptions& opt, FlowField* field_x) {
  const auto t0 = std::chrono::steady_clock::now();
  check_gap_map(gap);
  if (!(opt.tolerance > 0 && opt.tolerance < 1)) throw InputError("flow tolerance", "must be in (0, 1)");
  if (opt.threads < 0) throw InputError("flow threads", "must be >= 0");
  FlowConductance r;
  const FreeClusters fc = label_free_clusters(gap);
  r.percolates_x = fc.any_x();
  r.percolates_y = fc.any_y();
  r.free_fraction = double(fc.free_cells) / double(gap.size());
  double sum = 0;
  for (std::size_t k = 0; k < gap.size(); ++k) sum += gap.h[k];
  r.mean_gap = sum / double(gap.size());
  const ReynoldsSystem s = assemble(gap, fc);
  r.unknowns = std::size_t(s.a.rows());
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(s.a.rows(), 2);
  r.solver = "none";
  if (s.a.rows() > 0) {
    const FlowSolver which = resolve(opt.solver);
    const flow::LinearSolve ls =
        which == FlowSolver::amg ? flow::solve_amg(s.a, s.b, opt.tolerance) : flow::solve_cholmod(s.a, s.b);
    x = ls.x;
    r.solver = flow_solver_name(which);
    r.iterations = ls.iterations;
    r.residual = ls.residual;
  } else if (r.percolates_x || r.percolates_y) {
    r.solver = flow_solver_name(resolve(opt.solver));  // one free cell per cluster: nothing to solve
  }
  conductance_and_field(gap, s, x, r, field_x);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace wr
