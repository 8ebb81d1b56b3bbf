#pragma once
// Subcommand registration: each adds its options to the CLI11 app and returns the function
// that runs it after parsing. Commands only parse, call the libraries, and print.
#include <functional>

#include <CLI/CLI.hpp>

namespace wr::app {

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;  // returns the exit code
};

Command add_synth(CLI::App& root);
Command add_analyze(CLI::App& root);
Command add_fill(CLI::App& root);
Command add_contact(CLI::App& root);
Command add_bench(CLI::App& root);
Command add_sweep_coverage(CLI::App& root);
Command add_sweep_roughness(CLI::App& root);
Command add_report(CLI::App& root);
Command add_friction(CLI::App& root);
Command add_compound(CLI::App& root);
Command add_flow(CLI::App& root);

}  // namespace wr::app
