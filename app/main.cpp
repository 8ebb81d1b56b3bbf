// wetroad: tyre-road wet friction from road texture. This file only wires the subcommands.
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>

#include "app/commands.hpp"
#include "app/file_options.hpp"
#include "lib/core/errors.hpp"
#include "lib/io/staging.hpp"
#include "wetroad/version.hpp"

int main(int argc, char** argv) {
  // Before any thread exists (MPI, PETSc, OpenMP): an interrupted run removes its staging files.
  wr::install_interrupt_cleanup();
  CLI::App app{
      "wetroad - tyre-road wet friction from road texture.\n"
      "Synthesize or import road surfaces, analyze their texture (PSD, moments, summits, MPD),\n"
      "fill them with rain water, press and shear an elastic block on them (FEM or spectral),\n"
      "and sweep friction against water coverage.\n"
      "Units are SI (m, Pa) unless an option says otherwise."};
  app.set_version_flag("--version", std::string("wetroad ") + wr::kVersion);
  app.require_subcommand(1);
  app.fallthrough(false);

  const std::vector<wr::app::Command> commands = {wr::app::add_synth(app), wr::app::add_analyze(app), wr::app::add_fill(app), wr::app::add_friction(app), wr::app::add_compound(app), wr::app::add_contact(app), wr::app::add_flow(app),
                                                  wr::app::add_sweep_coverage(app), wr::app::add_sweep_roughness(app),
                                                  wr::app::add_report(app),
                                                  wr::app::add_bench(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "wetroad: error: " << e.what() << " (see wetroad --help)\n";
    return 2;
  }
  try {
    for (const auto& c : commands)
      if (c.sub->parsed()) {
        wr::app::check_file_options(*c.sub);
        return c.run();
      }
  } catch (const wr::InputError& e) {
    std::cerr << "wetroad: error: " << e.what() << "\n";
    return 2;
  } catch (const wr::NumericalError& e) {
    std::cerr << "wetroad: error: " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "wetroad: error: out of memory\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "wetroad: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
