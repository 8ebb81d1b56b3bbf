#pragma once
// Which linear solver the FEM's CG uses in its active-set solves: a sparse Cholesky
// factorisation (SuiteSparse CHOLMOD through PETSc on one rank; MUMPS across ranks, CHOLMOD
// being sequential) or the AMG preconditioner (amg_hierarchy.hpp). A factorisation makes CG
// exact in one iteration and is reused as the preconditioner of the next active set, like the
// AMG hierarchy; its cost grows faster than linearly with the block (fill-in of a 3-D mesh),
// so beyond a crossover the AMG wins. automatic chooses by the block's node count against that
// crossover, measured (docs/performance.md "Direct or AMG").
#include <string>

namespace wr {

enum class LinearSolver { automatic, direct, amg, gmg };

// Newton's systems (--iteration newton) always take the AMG path: they can be indefinite, which
// CG detects and a Cholesky factorisation does not tolerate, and they carry curvature blocks the
// matrix-free operator does not.
// automatic, in this order:
// - Newton: AMG;
// - from kGmgMinNodes nodes: the matrix-free geometric multigrid (gmg). With the node-stencil
//   kernel, on thesis-like surfaces at refine 1 (2 ranks, 2026-12-07), it pressed 32k, 144k and
//   325k nodes in 0.31x, 0.36x and 0.28x AMG's time and sheared 32k nodes in 0.34x; at refine 2
//   (1.05M nodes) a Signorini iteration took 0.245x AMG's time with 0.21x its memory
//   (docs/performance.md "Geometric multigrid against AMG");
// - a shear test: AMG (the direct solver was 1.5-1.9x slower in shear at every size measured);
// - direct up to kDirectSolverMaxNodes nodes on one rank (10-28 % faster pressing 1-11k nodes),
//   AMG above and on several ranks (MUMPS is not measured to win there).
// scripts/bench-fem-solver.sh (docs/performance.md "Direct or AMG", 2026-12-06).
inline constexpr double kDirectSolverMaxNodes = 20000;
inline constexpr double kGmgMinNodes = 20000;

// What the block will solve, for automatic's choice.
struct LinearSolverUse {
  bool shear = false;
  bool newton = false;
};
// `requested` unless it is automatic; then the rule above.
LinearSolver resolve_linear_solver(LinearSolver requested, double nodes, int ranks, LinearSolverUse use = {});

// "auto", "direct", "amg", "gmg"; InputError(option, ...) for anything else.
LinearSolver parse_linear_solver(const std::string& text, const std::string& option);
const char* linear_solver_name(LinearSolver s);

}  // namespace wr
