// `wetroad bench ...`: benchmarks and long validations (bench/); each bench registers itself
// (app/bench_cli.hpp), and this file runs the one asked for.
#include <memory>
#include <vector>

#include "app/bench_cli.hpp"
#include "lib/io/output_set.hpp"

namespace wr::app {

Command add_bench(CLI::App& root) {
  CLI::App* b = root.add_subcommand("bench", "benchmarks and long validations (not part of make test)");
  b->require_subcommand(1);
  auto entries = std::make_shared<std::vector<BenchEntry>>();
  for (auto add : {&add_speed_bench, &add_summits_bench, &add_water_bench, &add_coverage_bench, &add_friction_bench, &add_long_profile_bench, &add_spectral_speed_bench, &add_spectral_shear_bench, &add_kappa_bench, &add_spectral_vs_fem_bench, &add_accuracy_bench, &add_mesh_convergence_bench, &add_hertz_bench, &add_spot_bench, &add_obstacle_rays_bench, &add_flow_bench, &add_percolation_bench, &add_squeeze_bench, &add_sliding_bench, &add_sliding_convergence_bench, &add_fem_operator_bench})
    entries->push_back(add(*b));
  return {b, [entries] {
            for (const BenchEntry& e : *entries) {
              if (!e.sub->parsed()) continue;
              // Benchmarks write at their end, after minutes: try the outputs first (the
              // writers then write them atomically, each on its own).
              OutputSet preflight(false);
              if (e.input) preflight.input(*e.input);
              if (e.json) preflight.add("--json", *e.json);
              if (e.plot) preflight.add("--plot", *e.plot);
              for (const auto& [name, path] : e.more_outputs) preflight.add(name, *path);
              return e.run();
            }
            return 2;
          }};
}

}  // namespace wr::app
