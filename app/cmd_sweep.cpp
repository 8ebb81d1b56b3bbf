// `wetroad sweep-coverage`: friction against water coverage (lib/sweep/coverage_sweep.hpp).
// Runs are spread over MPI ranks, checkpointed one file per run, resumable (--resume).
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "app/commands.hpp"
#include "app/synth_options.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/provenance.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/sweep/coverage_sweep.hpp"
#include "lib/sweep/sweep_engine.hpp"
#include "reports/sweep_outputs.hpp"
#include "wetroad/version.hpp"

namespace wr::app {
namespace {

struct SweepCli {
  std::string surface, out, csv, json, plots, model = "fem", tiling = "torus";
  SynthOptions synth;
  std::vector<double> coverages = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
  int count = 0;
  double max_coverage = 0.8;
  int realizations = 1, connectivity = 4, threads = 0;
  ContactScene scene;
  bool resume = false, quiet = false;
};

std::string checkpoint_dir(const std::string& out) { return out + ".runs"; }

CoverageSweepSpec make_spec(const SweepCli& c) {
  CoverageSweepSpec s;
  if (c.count > 0) {
    if (!(c.max_coverage > 0 && c.max_coverage < 1)) throw InputError("--max-coverage", "must lie in (0, 1)");
    for (int k = 0; k <= c.count; ++k) s.coverages.push_back(c.max_coverage * k / c.count);
  } else {
    s.coverages = c.coverages;
  }
  s.realizations = c.realizations;
  const bool synthetic = c.synth.any_given();
  if (synthetic == !c.surface.empty())
    throw InputError("--surface", "give either a surface file or synthesis options (--scene, --size, ...), not both");
  if (synthetic) s.synth = resolve_synth_options(c.synth);
  s.surface_path = c.surface;
  s.scene = c.scene;
  try {
    s.scene.model = parse_model(c.model);
  } catch (const std::invalid_argument& e) {
    throw InputError("--model", e.what());
  }
  if (c.tiling != "torus" && c.tiling != "3x3") throw InputError("--tiling", "must be torus or 3x3");
  s.tiling = c.tiling == "torus" ? Tiling::torus : Tiling::three_by_three;
  s.connectivity = c.connectivity;
  if (s.connectivity != 4 && s.connectivity != 8) throw InputError("--connectivity", "must be 4 or 8");
  check_sweep_spec(s);
  return s;
}

void print_table(const nlohmann::json& table) {
  auto v = [](const nlohmann::json& j) { return j.is_number() ? j.get<double>() : NAN; };
  std::printf("  %8s %9s %8s %10s %10s %16s %10s %10s %12s %4s %6s\n", "target", "water", "coverage", "mu_peak",
              "mu/mu_dry", "+-95%", "A/A0 norm", "A/A0 peak", "pool [mm]", "n", "failed");
  for (const auto& r : table)
    std::printf("  %7.1f%% %9s %7.1f%% %10.4g %9.1f%% %15.1f%% %10.4f %10.4f %12.4f %4d %6d\n", 100 * v(r["target"]),
                r["water"].get<std::string>().c_str(), 100 * v(r["coverage"]["mean"]), v(r["mu_peak"]["mean"]),
                100 * v(r["mu_ratio"]["mean"]), 100 * v(r["mu_ratio"]["ci95"]), v(r["area_normal"]["mean"]),
                v(r["area_at_peak"]["mean"]), 1e3 * v(r["mean_pool_depth"]["mean"]), r["mu_peak"]["n"].get<int>(),
                r["failed"].get<int>());
}

int run_sweep(const SweepCli& c) {
  const CoverageSweepSpec spec = make_spec(c);
  const nlohmann::json spec_json = sweep_spec_json(spec);
  int argc = 1;
  char name[] = "wetroad";
  char* args[] = {name, nullptr};
  char** argv = args;
  PetscSession petsc(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  const bool talk = rank == 0 && !c.quiet;
  const auto t0 = std::chrono::steady_clock::now();

  const SweepCheckpoint cp(checkpoint_dir(c.out));
  const std::string& dir = cp.dir();
  cp.check(spec_json, c.resume);
  MPI_Barrier(PETSC_COMM_WORLD);
  if (rank == 0) cp.start(spec_json);
  const std::vector<CoverageRunKey> keys = plan_runs(spec);
  const auto before = cp.finished(int(keys.size()));
  const std::size_t finished_before = before.size();
  std::vector<int> pending;
  for (const auto& k : keys)
    if (!before.count(k.index)) pending.push_back(k.index);
  if (talk) {
    std::printf("coverage sweep: %zu runs (%zu coverages x %d realizations), model %s, %d rank(s)\n", keys.size(),
                spec.coverages.size(), spec.realizations, model_name(spec.scene.model), ranks);
    if (finished_before > 0)
      std::printf("  resuming: %zu runs finished earlier are kept, %zu to do\n", finished_before, pending.size());
    if (spec.scene.model == ContactModel::spectral)
      std::fprintf(stderr, "wetroad: warning: the spectral model is laterally periodic: its friction is not a finite "
                           "block's (flagged in every run's validity)\n");
    std::fflush(stdout);
  }
  // Each run alone on one rank (PETSC_COMM_SELF), so the answer does not depend on the rank
  // count; one rank per core, so threads only without MPI.
  const int threads = ranks > 1 ? 1 : (c.threads > 0 ? c.threads : hardware_threads());
  CoverageRunner runner(spec, PETSC_COMM_SELF, threads);
  const int all_failures = run_pending(
      cp, pending, PETSC_COMM_WORLD, [&](int i) { return runner.run(keys[std::size_t(i)]); },
      [&](const SweepRunDone& d) {
        const nlohmann::json& rec = *d.record;
        const CoverageRunKey& k = keys[std::size_t(d.index)];
        if (rec["status"] != "ok")
          std::fprintf(stderr, "wetroad: warning: run %d (coverage %.3g, realization %d) failed: %s\n", k.index,
                       k.target, k.realization, rec["message"].get<std::string>().c_str());
        if (c.quiet) return;
        const nlohmann::json& mu = rec.contains("contact") ? rec["contact"]["mu_peak"] : nlohmann::json(nullptr);
        std::fprintf(stderr, "  [rank %d] run %d/%zu: realization %d, coverage %.1f%% (%s) mu %s, %.1f s; about %s left\n",
                     rank, k.index + 1, keys.size(), k.realization, 100 * rec.value("coverage", 0.0),
                     rec.value("water", "-").c_str(), mu.is_number() ? std::to_string(mu.get<double>()).c_str() : "-",
                     rec["wall"]["total"].get<double>(), duration_text(d.seconds_left).c_str());
      });
  if (rank != 0) return all_failures > 0 ? 3 : 0;

  const std::map<int, nlohmann::json> done = cp.finished(int(keys.size()));
  std::vector<nlohmann::json> runs;
  for (const auto& [i, r] : done) runs.push_back(r);
  if (runs.size() != keys.size()) throw std::runtime_error("sweep: " + std::to_string(keys.size() - runs.size()) + " runs missing after the sweep");
  const nlohmann::json table = coverage_table(runs);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  int failed_total = 0;
  for (const auto& r : runs) failed_total += r["status"] != "ok";
  Provenance prov;
  prov.command = "sweep-coverage";
  prov.inputs = {{"surface", spec.surface_path}};
  prov.parameters = spec_json;
  prov.model = std::string(model_name(spec.scene.model)) + " contact scene per run (see each run's contact.validity)";
  prov.timings = {{"total", wall}, {"ranks", ranks}, {"runs_this_invocation", pending.size()}};
  const nlohmann::json sweep = {{"spec", spec_json}, {"table", table}, {"runs", runs}, {"failed_runs", failed_total},
                                {"checkpoint", dir}, {"provenance", prov.to_json()}};
  write_sweep_hdf5(c.out, sweep, coverage_layout());
  if (!c.csv.empty()) write_sweep_csv(c.csv, table, coverage_layout());
  if (!c.json.empty()) write_text_atomically(c.json, sweep.dump(1) + "\n");
  std::vector<std::string> charts;
  if (!c.plots.empty()) charts = write_coverage_plots(c.plots, sweep);
  if (!c.quiet) {
    print_table(table);
    std::printf("  wrote %s%s%s%s%s; checkpoint %s\n", c.out.c_str(), c.csv.empty() ? "" : (", " + c.csv).c_str(),
                c.json.empty() ? "" : (", " + c.json).c_str(), charts.empty() ? "" : ", charts in ",
                c.plots.c_str(), dir.c_str());
    std::printf("  wall %.1f s on %d rank(s)\n", wall, ranks);
  }
  for (const auto& r : runs)
    if (r["target"] == 0 && r["status"] == "ok" && !(r["contact"]["mu_peak"].get<double>() > 0))
      std::fprintf(stderr, "wetroad: warning: realization %d has no positive dry friction (mu %.3g): no wet/dry ratios "
                           "for it\n", r["realization"].get<int>(), r["contact"]["mu_peak"].get<double>());
  if (failed_total > 0) {
    std::fprintf(stderr, "wetroad: error: %d of %zu runs failed (kept in the outputs with their reasons, left out of "
                         "the means)\n", failed_total, runs.size());
    return 3;
  }
  return 0;
}

}  // namespace

Command add_sweep_coverage(CLI::App& root) {
  auto c = std::make_shared<SweepCli>();
  CLI::App* s = root.add_subcommand("sweep-coverage", "friction against water coverage (thesis Figure 5.25)");
  s->footer(
      "For each coverage: fill the surface's pools (drained up to the surface's drained limit, standing\n"
      "water beyond it), use the wet surface as the rigid obstacle, run the shear test (Problem A then B,\n"
      "as `wetroad contact`), and record mu, A/A0, the pools' mean depth and the wet surface's PSD.\n"
      "Coverage 0 is the dry surface; mu_wet/mu_dry is taken per realization. Every finished run is\n"
      "checkpointed in OUT.runs/; --resume continues a killed sweep. Under mpirun the runs are shared\n"
      "among the ranks (each run on one rank); results do not depend on the rank count.\n"
      "Example: wetroad sweep-coverage --scene default --size 32 --dx 9.375e-4 --coverages 0 0.2 0.4 0.6 \\\n"
      "           --uz 3e-3 --ux 1.5e-3 --out sweep.h5 --csv sweep.csv --plots charts\n"
      "         mpirun -np 2 wetroad sweep-coverage --surface road.h5 --count 8 --uz 9e-3 --ux 3e-3 --out s.h5");
  s->add_option("--surface", c->surface, "surface file (HDF5 height map or text grid); or give synthesis options");
  add_synth_options(*s, c->synth);
  s->add_option("--realizations", c->realizations, "independent synthetic surfaces (seeds seed, seed+1, ...)")
      ->capture_default_str();
  s->add_option("--coverages", c->coverages, "target water coverages, fractions in [0, 1), ascending (0 = dry)")
      ->capture_default_str();
  s->add_option("--count", c->count, "instead of --coverages: N+1 coverages evenly from 0 to --max-coverage");
  s->add_option("--max-coverage", c->max_coverage, "largest coverage of --count")->capture_default_str();
  s->add_option("--tiling", c->tiling, "drainage: torus (exact periodic) or 3x3 (the thesis's tiling)")
      ->capture_default_str();
  s->add_option("--connectivity", c->connectivity, "4 or 8 neighbours for water flow")->capture_default_str();
  s->add_option("--model", c->model, "contact model: fem (finite block) or spectral (periodic layer)")
      ->capture_default_str();
  s->add_option("--uz", c->scene.uz, "final normal displacement of the block's top, m")->required();
  s->add_option("--ux", c->scene.ux, "final tangential displacement of the top, m")->required();
  s->add_option("--steps", c->scene.normal_steps, "normal load steps")->capture_default_str();
  s->add_option("--shear-steps", c->scene.shear_steps, "shear steps")->capture_default_str();
  s->add_option("--refine", c->scene.refine, "contact-face spacing = surface spacing / refine")->capture_default_str();
  s->add_option("--E", c->scene.young, "Young's modulus, Pa")->capture_default_str();
  s->add_option("--nu", c->scene.poisson, "Poisson's ratio")->capture_default_str();
  s->add_option("--height", c->scene.height, "block height (spectral: layer thickness), m; 0 = a cube")
      ->capture_default_str();
  s->add_option("--tol", c->scene.tolerance, "relative change per geometry (Signorini) iteration")
      ->capture_default_str();
  s->add_option("--spectral-tol", c->scene.spectral_tolerance, "spectral normal solver tolerance")
      ->capture_default_str();
  s->add_option("--max-iterations", c->scene.max_iterations, "per step (0: the model's default)");
  s->add_option("--threads", c->threads, "threads of one process (ignored under mpirun: one rank per core)");
  s->add_option("--out", c->out, "result HDF5 (table, every run, provenance); OUT.runs/ holds the checkpoint")
      ->required();
  s->add_option("--csv", c->csv, "also write the table as CSV");
  s->add_option("--json", c->json, "also write everything as JSON");
  s->add_option("--plots", c->plots, "directory for the charts (SVG): mu ratio, A/A0, wet PSDs, pool depth");
  s->add_flag("--resume", c->resume, "continue the sweep checkpointed in OUT.runs/ (same parameters)");
  s->add_flag("-q,--quiet", c->quiet, "print nothing but warnings and errors");
  return {s, [c] { return run_sweep(*c); }};
}

}  // namespace wr::app
