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
// CG detects and a Cholesky factorisation does not tolerate.
// automatic: direct up to this many independent nodes on one rank, AMG above and on several
// ranks (MUMPS, the parallel factorisation, is not measured to win there). The press-and-shear
// driver (block_press_shear.hpp) takes AMG for a shear test before this rule: the direct solver
// was 1.5-1.9x slower in shear at every size measured, 10-28 % faster pressing 1-11k nodes.
// scripts/bench-fem-solver.sh (docs/performance.md "Direct or AMG", 2026-12-06).
inline constexpr double kDirectSolverMaxNodes = 20000;

// `requested` unless it is automatic; then direct for ranks == 1 and nodes <= kDirectSolverMaxNodes.
LinearSolver resolve_linear_solver(LinearSolver requested, double nodes, int ranks);

// "auto", "direct", "amg", "gmg"; InputError(option, ...) for anything else.
LinearSolver parse_linear_solver(const std::string& text, const std::string& option);
const char* linear_solver_name(LinearSolver s);

}  // namespace wr
