// `wetroad bench fem-operator`: the CLI of bench/bench_fem_operator.hpp.
#include <cstdio>
#include <memory>

#include "app/bench_cli.hpp"
#include "bench/bench_fem_operator.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/io/atomic_output.hpp"

namespace wr::app {
namespace {

struct FemOperatorCli {
  int size = 300;
  std::vector<int> refines = {1, 2};
  int repeats = 10;
  std::string json;
};

int run_fem_operator(const FemOperatorCli& c) {
  int argc = 1;
  char name[] = "wetroad";
  char* args[] = {name, nullptr};
  char** argv = args;
  PetscSession petsc(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const nlohmann::json r = bench::fem_operator(c.size, c.refines, c.repeats);
  if (rank != 0) return 0;
  std::printf("the block's stiffness product: assembled AIJ against matrix-free (%d x %d face per refine, 30 mm cube; best of %d)\n",
              c.size, c.size, c.repeats);
  std::printf("  %6s %5s %10s %12s %12s %8s %12s %12s %10s\n", "refine", "ranks", "dofs", "AIJ s", "matrix-free s", "speedup",
              "AIJ MiB", "m-free MiB", "rel diff");
  for (const auto& row : r["rows"])
    std::printf("  %6d %5d %10.0f %12.4f %12.4f %8.2f %12.1f %12.1f %10.1e\n", row["refine"].get<int>(), row["ranks"].get<int>(),
                row["dofs"].get<double>(), row["aij_product_s"].get<double>(), row["matrix_free_product_s"].get<double>(),
                row["speedup"].get<double>(), row["aij_bytes"].get<double>() / 1048576.0,
                row["matrix_free_bytes"].get<double>() / 1048576.0, row["relative_difference"].get<double>());
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

}  // namespace

BenchEntry add_fem_operator_bench(CLI::App& bench) {
  auto o = std::make_shared<FemOperatorCli>();
  CLI::App* s = bench.add_subcommand("fem-operator", "The FEM stiffness product: assembled AIJ against matrix-free (MPI ok; minutes at refine 2).");
  s->footer(
      "On the thesis scene's block (a --size x --size face of 30 mm at each refinement, a cube, the default grading):\n"
      "the assembled stiffness and the matrix-free one (lib/fem/matrix_free_stiffness.hpp) applied to the same random\n"
      "vector, their largest relative difference, the best time of --repeat products each and the memory they hold.\n"
      "Example: mpirun -np 2 wetroad bench fem-operator --refines 1 2 --json op.json");
  s->add_option("--size", o->size, "face cells per side at refine 1")->check(CLI::Range(2, 100000))->capture_default_str();
  s->add_option("--refines", o->refines, "face refinements")->check(CLI::Range(1, 64))->capture_default_str();
  s->add_option("--repeat", o->repeats, "products timed (the best is kept)")->check(CLI::Range(1, 10000))->capture_default_str();
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {s, [o] { return run_fem_operator(*o); }, &o->json, nullptr, nullptr};
}

}  // namespace wr::app
