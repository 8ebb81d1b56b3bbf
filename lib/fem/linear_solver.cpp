#include "lib/fem/linear_solver.hpp"

#include "lib/core/errors.hpp"

namespace wr {

LinearSolver resolve_linear_solver(LinearSolver requested, double nodes, int ranks, LinearSolverUse use) {
  if (requested != LinearSolver::automatic) return requested;
  if (use.newton) return LinearSolver::amg;
  if (nodes >= kGmgMinNodes) return LinearSolver::gmg;
  if (use.shear) return LinearSolver::amg;
  return ranks == 1 && nodes <= kDirectSolverMaxNodes ? LinearSolver::direct : LinearSolver::amg;
}

LinearSolver parse_linear_solver(const std::string& text, const std::string& option) {
  if (text == "auto") return LinearSolver::automatic;
  if (text == "direct") return LinearSolver::direct;
  if (text == "amg") return LinearSolver::amg;
  if (text == "gmg") return LinearSolver::gmg;
  throw InputError(option, "must be auto, direct, amg or gmg (got '" + text + "')");
}

const char* linear_solver_name(LinearSolver s) {
  switch (s) {
    case LinearSolver::direct: return "direct";
    case LinearSolver::amg: return "amg";
    case LinearSolver::gmg: return "gmg";
    default: return "auto";
  }
}

}  // namespace wr
