#pragma once
// The benches of `wetroad bench` (bench/): each registers its own subcommand with its own
// options, and says which of them are output files (checked before the work) and inputs.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.hpp"

namespace wr::app {

struct BenchEntry {
  CLI::App* sub = nullptr;
  std::function<int()> run;
  const std::string* json = nullptr;   // --json, where the bench has one
  const std::string* plot = nullptr;   // --plot
  const std::string* input = nullptr;  // an input file (--surface)
  std::vector<std::pair<std::string, const std::string*>> more_outputs = {};  // other output options by name
};

BenchEntry add_speed_bench(CLI::App& bench);  // app/bench_cli_surfaces.cpp
BenchEntry add_summits_bench(CLI::App& bench);  // app/bench_cli_surfaces.cpp
BenchEntry add_water_bench(CLI::App& bench);  // app/bench_cli_surfaces.cpp
BenchEntry add_coverage_bench(CLI::App& bench);  // app/bench_cli_surfaces.cpp
BenchEntry add_friction_bench(CLI::App& bench);  // app/bench_cli_surfaces.cpp
BenchEntry add_long_profile_bench(CLI::App& bench);  // app/bench_cli_surfaces.cpp
BenchEntry add_spectral_speed_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_spectral_shear_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_kappa_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_spectral_vs_fem_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_accuracy_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_mesh_convergence_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_hertz_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_spot_bench(CLI::App& bench);  // app/bench_cli_contact.cpp
BenchEntry add_obstacle_rays_bench(CLI::App& bench);  // app/bench_cli_geometry.cpp
BenchEntry add_flow_bench(CLI::App& bench);  // app/bench_cli_flow.cpp
BenchEntry add_percolation_bench(CLI::App& bench);  // app/bench_cli_flow.cpp
BenchEntry add_squeeze_bench(CLI::App& bench);  // app/bench_cli_flow.cpp
BenchEntry add_sliding_bench(CLI::App& bench);  // app/bench_cli_sliding.cpp
BenchEntry add_sliding_convergence_bench(CLI::App& bench);  // app/bench_cli_sliding.cpp
BenchEntry add_fem_operator_bench(CLI::App& bench);  // app/bench_cli_fem.cpp

}  // namespace wr::app
