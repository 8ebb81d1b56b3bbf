// `wetroad sweep-coverage` (lib/sweep/coverage_sweep.hpp) and `wetroad sweep-roughness`
// (lib/sweep/roughness_sweep.hpp). Runs are spread over MPI ranks, checkpointed one file per
// run, resumable (--resume): lib/sweep/sweep_engine.hpp.
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "app/commands.hpp"
#include "app/launch.hpp"
#include "app/print_summary.hpp"
#include "app/friction_options.hpp"
#include "app/scene_options.hpp"
#include "app/synth_options.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/number_text.hpp"
#include "lib/core/provenance.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "lib/sweep/coverage_sweep.hpp"
#include "lib/sweep/roughness_sweep.hpp"
#include "lib/sweep/sweep_engine.hpp"
#include "reports/sweep_outputs.hpp"
#include "roads/surface_import.hpp"

namespace wr::app {
namespace {

// The options every sweep shares: the friction model (a contact scene or the hysteresis
// model) and the outputs.
struct SweepCommonCli {
  std::string model = "fem", out, csv, json, plots;
  SceneCli sc;  // every scene option (app/scene_options.hpp), with the sweeps' defaults
  std::string compound, test = "e274-ribbed";
  double water_film = 0;
  bool no_film = false, band = false;
  CLI::Option* film_opt = nullptr;
  double pressure = 3e5, temperature = 20, speed = kLockedWheelSpeed;
  std::string friction_q1, hysteresis_model = "persson";
  std::size_t exact_refine = kDefaultExactRefine;
  bool flash = false;
  CLI::Option* q1_opt = nullptr;
  int threads = 0;
  bool resume = false, quiet = false;
  double step_lines_s = 10;  // --progress: a run's step is reported when it took this long
  // Options only the contact models read, and options only the hysteresis model reads: given
  // with the other kind of model they would be silently ignored, so they are refused by name.
  std::vector<CLI::Option*> contact_only, hysteresis_only;
};

// The options of `group` given on the command line, refused by name with `why`.
void refuse_given(const std::vector<CLI::Option*>& group, const std::string& why) {
  for (const CLI::Option* o : group)
    if (o->count() > 0) throw InputError(o->get_name(), why);
}

void add_common_options(CLI::App& s, SweepCommonCli& c) {
  s.add_option("--model", c.model, "friction model: fem (finite block), spectral (periodic layer), auto (the ladder's "
              "cheapest contact model valid for friction): elastostatic friction; or hysteresis (Persson's mu at --speed)")
      ->capture_default_str();
  const std::size_t before_scene = s.get_options().size();
  add_scene_options(s, c.sc);
  const auto scene_options = s.get_options();
  c.contact_only.assign(scene_options.begin() + std::ptrdiff_t(before_scene), scene_options.end());
  c.contact_only.push_back(
      s.add_option("--progress", c.step_lines_s,
                   "contact models: report each load step of a run as it ends if it took at least this long, s "
                   "(0: every step; a step that ends a run unconverged always)")
          ->type_name("SECONDS")
          ->check(CLI::NonNegativeNumber)
          ->capture_default_str());
  c.hysteresis_only = {
      s.add_option("--compound", c.compound, "hysteresis: compound JSON (default share/compounds/synthetic-tread.json)")->type_name("FILE"),
      s.add_option("--pressure", c.pressure, "hysteresis: nominal pressure sigma0, Pa")->capture_default_str(),
      s.add_option("--temperature", c.temperature, "hysteresis: temperature, deg C")->capture_default_str(),
      s.add_option("--speed", c.speed, "hysteresis: sliding speed, m/s (default 17.9: the locked wheel at 64 km/h)"),
      c.q1_opt = s.add_option("--friction-q1", c.friction_q1, "hysteresis: spectrum cut-off q1, 1/m or rms-slope[:S] (as `friction --q1`)")->type_name("Q1"),
      s.add_flag("--flash-temperature", c.flash, "hysteresis: with the flash temperature (as `friction`)"),
      c.film_opt = s.add_option("--water-film", c.water_film, "hysteresis: water film ahead of the tyre, m (default: the test's, 0.5e-3)"),
      s.add_option("--test", c.test, "hysteresis: skid test and tyre, e274-ribbed, e274-smooth or a JSON file (as `friction`)")
          ->type_name("FILE")
          ->capture_default_str(),
      s.add_flag("--no-film", c.no_film, "hysteresis: no water film, the drained road's hysteresis friction only"),
      s.add_flag("--band", c.band, "hysteresis: each run's skid-number band over the inputs' default ranges (as `friction --band`)"),
      s.add_option("--hysteresis-model", c.hysteresis_model,
                   "hysteresis: persson (Persson's theory), viscoelastic (exact steady sliding on each map, seconds per "
                   "speed, the map's band) or auto (as `friction --model`)")
          ->capture_default_str(),
      s.add_option("--exact-refine", c.exact_refine, "hysteresis: the exact rung's grid refinement (as `friction --exact-refine`)")
          ->check(CLI::Range(1, 16))
          ->capture_default_str()};
  s.add_option("--threads", c.threads, "threads of one process (ignored under mpirun: one rank per core)")->check(CLI::NonNegativeNumber);
  s.add_option("--out", c.out, "result HDF5 (table, every run, provenance); OUT.runs/ holds the checkpoint")->type_name("OUTPUT")->required();
  s.add_option("--csv", c.csv, "also write the table as CSV")->type_name("OUTPUT");
  s.add_option("--json", c.json, "also write everything as JSON")->type_name("OUTPUT");
  s.add_option("--plots", c.plots, "directory for the charts (SVG)")->type_name("FOLDER");
  s.add_flag("--resume", c.resume, "continue the sweep checkpointed in OUT.runs/ (same parameters)");
  s.add_flag("-q,--quiet", c.quiet, "print nothing but warnings and errors");
}

// --model: fem, spectral, or auto. Sweeps measure friction, so auto asks the ladder for the
// cheapest model valid for a shear test (lib/contact/model_ladder.hpp) and says why.
ContactModel parse_sweep_model(const std::string& name, bool quiet) {
  if (name == "auto") {
    ContactRequest req;
    req.shear = true;
    const ModelChoice choice = choose_model(req);
    std::string why;
    for (const auto& [m, checks] : choice.considered)
      for (const auto& v : checks)
        if (!v.passed) why += std::string("; ") + model_name(m) + ": " + v.name + " failed";
    if (!choice.found) throw InputError("--model auto", "no model passes its validity checks" + why);
    if (!quiet && launch_rank_and_size().first == 0)
      std::fprintf(stderr, "model auto: %s, the cheapest model valid for friction%s\n", model_name(choice.model), why.c_str());
    return choice.model;
  }
  try {
    return parse_model(name);
  } catch (const std::invalid_argument& e) {
    throw InputError("--model", e.what());
  }
}

// The hysteresis model's scene from the common options (model "hysteresis"); nullopt for the
// contact models, which need --uz and --ux.
std::optional<FrictionScene> hysteresis_scene(const SweepCommonCli& c) {
  if (c.threads < 0) throw InputError("--threads", "must be >= 0 (0: all hardware threads)");
  if (c.model != "hysteresis") {
    parse_sweep_model(c.model, true);  // a bad name is named before any option it would need
    refuse_given(c.hysteresis_only, "is an option of --model hysteresis, not of the contact model " + c.model);
    if (!c.sc.uz->count()) throw InputError("--uz", "required by the contact models (fem, spectral, auto)");
    if (!c.sc.ux->count()) throw InputError("--ux", "required by the contact models (fem, spectral, auto)");
    return std::nullopt;
  }
  if (c.sc.uz->count() || c.sc.ux->count())
    throw InputError(c.sc.uz->count() ? "--uz" : "--ux", "the hysteresis model has no block to displace (see --speed)");
  refuse_given(c.contact_only, "is a contact-model option; --model hysteresis does not use it");
  FrictionScene s;
  s.compound_path = c.compound.empty() ? default_compound_path() : c.compound;
  s.compound = read_compound_json(s.compound_path);
  s.options.pressure = c.pressure;
  s.options.temperature = c.temperature;
  s.options.flash_temperature = c.flash;
  s.model = parse_hysteresis_model(c.hysteresis_model, "--hysteresis-model");
  s.exact_refine = c.exact_refine;
  if (c.q1_opt->count()) apply_q1_option(c.friction_q1, "--friction-q1", s);
  s.speeds = {c.speed};
  apply_film_options(c.no_film, *c.film_opt, c.water_film, c.test, s);
  if (c.band) {
    if (!s.film) throw InputError("--band", "the band is the skid number's: not with --no-film");
    s.band = UncertaintySetup{};
  }
  check_friction_scene(s);
  return s;
}

// "  [rank 1] run 3/6, step 4: uz 9 mm, ux 2 mm, mu 0.0412, A/A0 0.5312, 138 s, 77 Signorini
// iterations" on stderr as each step ends; a step that ends the run says why.
void print_sweep_step(int rank, int run, int runs, int step, const ContactStep& s, bool fem) {
  std::string extra;
  if (fem) extra += ", " + std::to_string(s.signorini_iterations) + " Signorini iterations";
  if (s.failed_attempts > 0)
    extra += " (after " + std::to_string(s.failed_attempts) + (s.failed_attempts == 1 ? " failed attempt" : " failed attempts") +
             " at a longer step)";
  if (!s.converged) extra += "; not converged: " + s.message;
  // Friction is only asked of shear steps; a press step's Fx / Fz is a by-product.
  const std::string mu = s.ux != 0 ? ", mu " + number_text(s.mu, 4) : "";
  std::fprintf(stderr, "  [rank %d] run %d/%d, step %d: uz %.4g mm, ux %.4g mm%s, A/A0 %.4f, %.*f s%s\n", rank, run,
               runs, step, 1e3 * s.uz, 1e3 * s.ux, mu.c_str(), s.area_fraction, s.wall_s < 10 ? 1 : 0, s.wall_s,
               extra.c_str());
  std::fflush(stderr);
}

// What distinguishes one sweep kind from the other in the driver below.
struct SweepKind {
  std::string command;                       // for the provenance
  const SweepTableLayout* layout = nullptr;
  nlohmann::json spec;
  int runs = 0;
  std::string headline;                      // printed at the start
  // One run; `on_step` hears of each of its contact run's load steps as it ends (may be empty).
  std::function<nlohmann::json(int index, int threads, const StepListener& on_step)> run;
  std::function<std::string(const nlohmann::json& record)> describe;  // progress line
  std::function<nlohmann::json(const std::vector<nlohmann::json>&)> table;
  std::function<void(nlohmann::json& sweep)> extend;         // extra entries (thesis rows), may be empty
  std::function<std::vector<std::string>(const std::string& dir, const nlohmann::json& sweep)> plots;
  std::function<void(const nlohmann::json& sweep)> print;
};

// PETSc/MPI start, checkpoint, runs over the ranks, then (rank 0) the table and every output.
int drive_sweep(const SweepCommonCli& c, const SweepKind& k) {
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
  // Every output checked (and staged) before the first run; rank 0 writes them at the end.
  OutputSet outputs(rank == 0);
  if (k.spec.contains("surface") && k.spec["surface"].contains("path")) outputs.input(k.spec["surface"]["path"]);
  const std::string out_path = outputs.add("--out", c.out), csv_path = outputs.add("--csv", c.csv),
                    json_path = outputs.add("--json", c.json), plots_dir = outputs.add_directory("--plots", c.plots);

  SweepCheckpoint cp(c.out + ".runs");
  cp.check(k.spec, c.resume);
  cp.start(k.spec, PETSC_COMM_WORLD);
  const auto before = cp.finished(k.runs);
  std::vector<int> pending;
  for (int i = 0; i < k.runs; ++i)
    if (!before.count(i)) pending.push_back(i);
  if (talk) {
    std::printf("%s, %d rank(s)\n", k.headline.c_str(), ranks);
    if (!before.empty()) std::printf("  resuming: %zu runs finished earlier are kept, %zu to do\n", before.size(), pending.size());
    std::fflush(stdout);
  }
  if (rank == 0 && k.spec["scene"]["model"] == "spectral")
    std::fprintf(stderr, "wetroad: warning: the spectral model is laterally periodic: its friction is not a finite "
                         "block's (flagged in every run's validity)\n");
  // Each run alone on one rank (PETSC_COMM_SELF), so the answer does not depend on the rank
  // count; one rank per core, so threads only without MPI.
  const int threads = ranks > 1 ? 1 : (c.threads > 0 ? c.threads : hardware_threads());
  const bool fem = k.spec["scene"]["model"] == "fem";
  const int all_failures = run_pending(
      cp, pending, PETSC_COMM_WORLD,
      [&](int i) {
        // A FEM run at the thesis's scale takes a quarter of an hour: a line per slow load step.
        int step = 0;
        const auto on_step = [&](const ContactStep& s) {
          ++step;
          if (!c.quiet && (s.wall_s >= c.step_lines_s || !s.converged)) print_sweep_step(rank, i + 1, k.runs, step, s, fem);
        };
        return k.run(i, threads, on_step);
      },
      [&](const SweepRunDone& d) {
        const nlohmann::json& rec = *d.record;
        if (rec["status"] != "ok")
          std::fprintf(stderr, "wetroad: warning: run %d failed: %s\n", d.index, rec["message"].get<std::string>().c_str());
        if (!c.quiet)
          std::fprintf(stderr, "  [rank %d] run %d/%d: %s, %.1f s; about %s left\n", rank, d.index + 1, k.runs,
                       k.describe(rec).c_str(), rec["wall"]["total"].get<double>(), duration_text(d.seconds_left).c_str());
      });
  if (rank != 0) return all_failures > 0 ? 3 : 0;

  std::vector<nlohmann::json> runs;
  for (auto& [i, r] : cp.finished(k.runs)) runs.push_back(std::move(r));
  if (int(runs.size()) != k.runs)
    throw std::runtime_error("sweep: " + std::to_string(k.runs - int(runs.size())) + " runs missing after the sweep");
  const nlohmann::json table = k.table(runs);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  int failed_total = 0;
  for (const auto& r : runs) failed_total += r["status"] != "ok";
  Provenance prov;
  prov.command = k.command;
  prov.inputs = k.spec.contains("surface") ? k.spec["surface"] : nlohmann::json::object();
  prov.parameters = k.spec;
  prov.model = k.spec["scene"]["model"] == "hysteresis"
                   ? std::string("hysteresis friction per run (Persson; see each run's contact.validity)")
                   : k.spec["scene"]["model"].get<std::string>() + " contact scene per run (see each run's contact.validity)";
  prov.timings = {{"total", wall}, {"ranks", ranks}, {"runs_this_invocation", pending.size()}};
  nlohmann::json sweep = {{"spec", k.spec},          {"table", table},       {"runs", runs},
                          {"failed_runs", failed_total}, {"checkpoint", cp.dir()}, {"provenance", prov.to_json()}};
  if (k.extend) k.extend(sweep);
  write_sweep_hdf5(out_path, sweep, *k.layout);
  if (!c.csv.empty()) write_sweep_csv(csv_path, table, *k.layout);
  if (!c.json.empty()) write_text_atomically(json_path, sweep.dump(1) + "\n");
  std::vector<std::string> charts;
  if (!c.plots.empty()) charts = k.plots(plots_dir, sweep);
  outputs.commit();
  if (!c.quiet) {
    k.print(sweep);
    std::printf("  wrote %s%s%s%s%s; checkpoint %s\n", c.out.c_str(), c.csv.empty() ? "" : (", " + c.csv).c_str(),
                c.json.empty() ? "" : (", " + c.json).c_str(), charts.empty() ? "" : ", charts in ", c.plots.c_str(),
                cp.dir().c_str());
    std::printf("  wall %.1f s on %d rank(s)\n", wall, ranks);
  }
  // Results outside their model's validity are flagged in every output; say so here too.
  int invalid = 0;
  std::string why;
  for (const auto& r : runs)
    if (r.contains("contact") && r["contact"]["validity"].is_object() && !r["contact"]["validity"].value("valid", true)) {
      ++invalid;
      for (const auto& ch : r["contact"]["validity"]["checks"])
        if (why.empty() && !ch.value("passed", true)) why = ch.value("check", "") + ": " + ch.value("detail", "");
    }
  if (invalid > 0)
    std::fprintf(stderr, "wetroad: warning: %d of %zu runs are outside their model's validity (%s)\n", invalid,
                 runs.size(), why.c_str());
  if (failed_total > 0) {
    std::fprintf(stderr, "wetroad: error: %d of %zu runs failed (kept in the outputs with their reasons, left out of "
                         "the means)\n", failed_total, runs.size());
    return 3;
  }
  return 0;
}

double value_or_nan(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : NAN; }

// A table cell: `v` printed with `format` (one conversion), or "-" when there is no value
// (every run of the row failed); right-aligned to `width`.
std::string cell(double v, const char* format, int width) {
  char b[64];
  if (std::isfinite(v)) std::snprintf(b, sizeof b, format, v);
  else std::snprintf(b, sizeof b, "-");
  char out[80];
  std::snprintf(out, sizeof out, "%*s", width, b);
  return out;
}

// ---- sweep-coverage ----

struct CoverageCli {
  SweepCommonCli common;
  std::string surface, tiling = "torus";
  SynthOptions synth;
  std::vector<double> coverages = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
  int count = 0;
  CLI::Option *count_opt = nullptr, *coverages_opt = nullptr, *max_coverage_opt = nullptr;
  double max_coverage = 0.8;
  int realizations = 1, connectivity = 4;
};

CoverageSweepSpec coverage_spec(const CoverageCli& c) {
  CoverageSweepSpec s;
  if (c.count_opt->count() > 0 && c.coverages_opt->count() > 0)
    throw InputError("--count", "give either --count (with --max-coverage) or --coverages, not both");
  if (c.max_coverage_opt->count() > 0 && c.count_opt->count() == 0)
    throw InputError("--max-coverage", "only sets the range of --count N; give --count, or list --coverages");
  if (c.count_opt->count() > 0) {
    if (c.count < 1 || c.count > 1000) throw InputError("--count", "must be 1 ... 1000 (coverages beyond the dry one)");
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
  if (!synthetic) {  // bad files fail here, not in every run
    const LoadedSurface surface = load_surface(c.surface);
    require_periodic_map(surface, "the contact scene repeats the surface");
    if (launch_rank_and_size().first == 0) print_load_warnings(surface);
  }
  SceneCli sc = c.common.sc;
  finish_scene_options(sc);
  s.scene = sc.scene;
  s.hysteresis = hysteresis_scene(c.common);
  if (!s.hysteresis) s.scene.model = parse_sweep_model(c.common.model, c.common.quiet);
  if (c.tiling != "torus" && c.tiling != "3x3") throw InputError("--tiling", "must be torus or 3x3");
  s.tiling = c.tiling == "torus" ? Tiling::torus : Tiling::three_by_three;
  s.connectivity = c.connectivity;
  check_sweep_spec(s);
  return s;
}

void print_coverage_table(const nlohmann::json& sweep) {
  auto v = value_or_nan;
  // The hysteresis model's mu is the local sealing model's; the homogeneous one stands beside it.
  const bool hysteresis = sweep["spec"]["scene"]["model"] == "hysteresis";
  std::printf("  %8s %9s %8s %10s %10s %16s%s %10s %10s %12s %4s %6s\n", "target", "water", "coverage", "mu_peak",
              "mu/mu_dry", "+-95%", hysteresis ? "    hom/dry" : "", "A/A0 norm", "A/A0 peak", "pool [mm]", "n", "failed");
  for (const auto& r : sweep["table"])
    std::printf("  %s %9s %s %s %s %s%s %s %s %s %4d %6d\n", cell(100 * v(r["target"]), "%.1f%%", 8).c_str(),
                r["water"].get<std::string>().c_str(), cell(100 * v(r["coverage"]["mean"]), "%.1f%%", 8).c_str(),
                cell(v(r["mu_peak"]["mean"]), "%.4g", 10).c_str(), cell(100 * v(r["mu_ratio"]["mean"]), "%.1f%%", 10).c_str(),
                cell(100 * v(r["mu_ratio"]["ci95"]), "%.1f%%", 16).c_str(),
                hysteresis ? (" " + cell(100 * v(r["mu_ratio_homogeneous"]["mean"]), "%.1f%%", 10)).c_str() : "", cell(v(r["area_normal"]["mean"]), "%.4f", 10).c_str(),
                cell(v(r["area_at_peak"]["mean"]), "%.4f", 10).c_str(),
                cell(1e3 * v(r["mean_pool_depth"]["mean"]), "%.4f", 12).c_str(), r["mu_peak"]["n"].get<int>(),
                r["failed"].get<int>());
  for (const auto& r : sweep["runs"])
    if (r["target"] == 0 && r["status"] == "ok" && !(r["contact"]["mu_peak"].get<double>() > 0))
      std::fprintf(stderr, "wetroad: warning: realization %d has no positive dry friction (mu %.3g): no wet/dry ratios "
                           "for it\n", r["realization"].get<int>(), r["contact"]["mu_peak"].get<double>());
}

int run_sweep_coverage(const CoverageCli& c) {
  const CoverageSweepSpec spec = coverage_spec(c);
  const std::vector<CoverageRunKey> keys = plan_runs(spec);
  // One runner per process: it keeps the last realization's surface and drained limit.
  auto runner = std::make_shared<std::unique_ptr<CoverageRunner>>();
  SweepKind k;
  k.command = "sweep-coverage";
  k.layout = &coverage_layout();
  k.spec = with_surface_digest(sweep_spec_json(spec));
  k.runs = int(keys.size());
  k.headline = "coverage sweep: " + std::to_string(keys.size()) + " runs (" + std::to_string(spec.coverages.size()) +
               " coverages x " + std::to_string(spec.realizations) + " realizations), model " +
               (spec.hysteresis ? "hysteresis" : model_name(spec.scene.model));
  k.run = [spec, keys, runner](int i, int threads, const StepListener& on_step) {
    if (!*runner) *runner = std::make_unique<CoverageRunner>(spec, PETSC_COMM_SELF, threads);
    return (*runner)->run(keys[std::size_t(i)], on_step);
  };
  k.describe = [](const nlohmann::json& r) {
    char b[160];
    std::snprintf(b, sizeof b, "realization %d, coverage %.1f%% (%s), mu %.4g", r["realization"].get<int>(),
                  100 * r.value("coverage", 0.0), r.value("water", "-").c_str(),
                  r.contains("contact") ? value_or_nan(r["contact"]["mu_peak"]) : NAN);
    return std::string(b);
  };
  k.table = coverage_table;
  k.plots = write_coverage_plots;
  k.print = print_coverage_table;
  return drive_sweep(c.common, k);
}

// ---- sweep-roughness ----

struct RoughnessCli {
  SweepCommonCli common;
  std::string dataset = "A";
  std::vector<double> values;
  int realizations = 10;
  SynthOptions synth;  // overrides of the dataset's surface (a coarser grid for quick runs)
};

RoughnessSweepSpec roughness_spec(const RoughnessCli& c) {
  RoughnessSweepSpec s = roughness_dataset(c.dataset);
  if (!c.values.empty()) s.values = c.values;
  s.realizations = c.realizations;
  // Surface options given on the command line replace the dataset's (the swept parameter wins).
  if (c.synth.any_given()) {
    if (c.synth.given("--scene")) throw InputError("--scene", "the dataset is the scene; override single options");
    const SynthParams o = resolve_synth_options(c.synth);
    if (c.synth.given("--size") || c.synth.given("--nx")) s.base.nx = o.nx;
    if (c.synth.given("--size") || c.synth.given("--ny")) s.base.ny = o.ny;
    if (c.synth.given("--dx")) s.base.dx = o.dx;
    if (c.synth.given("--h0")) s.base.h0 = o.h0;
    if (c.synth.given("--hurst")) s.base.hurst = o.hurst;
    if (c.synth.given("--q0-ratio")) s.base.q0_ratio = o.q0_ratio;
    if (c.synth.given("--q1")) s.base.q1 = o.q1;
    if (c.synth.given("--oversample")) s.base.oversample = o.oversample;
    if (c.synth.given("--sampling")) s.base.sampling = o.sampling;
    if (c.synth.given("--seed")) s.base.seed = o.seed;
  }
  SceneCli sc = c.common.sc;
  finish_scene_options(sc);
  s.scene = sc.scene;
  s.hysteresis = hysteresis_scene(c.common);
  if (!s.hysteresis) s.scene.model = parse_sweep_model(c.common.model, c.common.quiet);
  check_roughness_spec(s);
  return s;
}

void print_roughness_table(const nlohmann::json& sweep) {
  auto v = value_or_nan;
  std::printf("  %-20s %9s %9s %8s %9s %9s %8s %8s %4s %6s\n", "surfaces", "mu_peak", "+-95%", "CoV", "A/A0 peak",
              "A/A0 norm", "kappa", "h0 [mm]", "n", "failed");
  for (const auto& r : sweep["table"])
    std::printf("  %-20s %s %s %s %s %s %s %s %4d %6d\n", r["label"].get<std::string>().c_str(),
                cell(v(r["mu_peak"]["mean"]), "%.4g", 9).c_str(), cell(v(r["mu_peak"]["ci95"]), "%.2g", 9).c_str(),
                cell(100 * v(r["mu_peak"]["cov"]), "%.1f%%", 8).c_str(), cell(v(r["area_at_peak"]["mean"]), "%.4f", 9).c_str(),
                cell(v(r["area_normal"]["mean"]), "%.4f", 9).c_str(), cell(v(r["kappa"]["mean"]), "%.3f", 8).c_str(),
                cell(1e3 * v(r["h0"]["mean"]), "%.4f", 8).c_str(), r["mu_peak"]["n"].get<int>(), r["failed"].get<int>());
  if (!sweep["table"].empty() && sweep["table"][0].contains("sn") && sweep["table"][0]["sn"]["n"].get<int>() > 0) {
    std::printf("  wet at speed (the test's film): skid number and speed constant (mean over realizations)\n");
    std::printf("  %-20s %9s %9s %8s %11s %11s\n", "surfaces", "MPD [mm]", "SN", "+-95%", "Sp [km/h]", "E1960 Sp");
    for (const auto& r : sweep["table"]) {
      const double mpd = 1e3 * v(r["mpd"]["mean"]);
      std::printf("  %-20s %s %s %s %s %s\n", r["label"].get<std::string>().c_str(), cell(mpd, "%.3f", 9).c_str(),
                  cell(v(r["sn"]["mean"]), "%.1f", 9).c_str(), cell(v(r["sn"]["ci95"]), "%.2g", 8).c_str(),
                  cell(v(r["sp_kmh"]["mean"]), "%.0f", 11).c_str(), cell(14.2 + 89.7 * mpd, "%.1f", 11).c_str());
    }
  }
  if (!sweep["thesis"].empty()) {
    std::printf("  the thesis (Tables D.1-D.3, C.1; 300 x 300, dGamma = dtheta/2, uz 9 mm; A/A0 is its A'):\n");
    for (const auto& t : sweep["thesis"])
      std::printf("  %-20s %s %9s %s %s %9s %s\n", t["label"].get<std::string>().c_str(), cell(v(t["mu"]), "%.4g", 9).c_str(), "",
                  cell(100 * v(t["mu_cov"]), "%.1f%%", 8).c_str(), cell(v(t["area"]), "%.4f", 9).c_str(), "",
                  cell(t.contains("kappa") ? v(t["kappa"]) : NAN, "%.3f", 8).c_str());
  }
}

int run_sweep_roughness(const RoughnessCli& c) {
  const RoughnessSweepSpec spec = roughness_spec(c);
  SweepKind k;
  k.command = "sweep-roughness";
  k.layout = &roughness_layout();
  k.spec = with_surface_digest(roughness_spec_json(spec));
  k.runs = roughness_run_count(spec);
  k.headline = "roughness sweep, dataset " + spec.dataset + ": " + std::to_string(k.runs) + " runs (" +
               std::to_string(spec.values.size()) + " values of " + parameter_name(spec.parameter) + " x " +
               std::to_string(spec.realizations) + " realizations), " + std::to_string(spec.base.nx) + " x " +
               std::to_string(spec.base.ny) + " surfaces, model " + (spec.hysteresis ? "hysteresis" : model_name(spec.scene.model));
  k.run = [spec](int i, int threads, const StepListener& on_step) {
    return run_roughness_point(spec, i, PETSC_COMM_SELF, threads, on_step);
  };
  k.describe = [](const nlohmann::json& r) {
    char b[160];
    const bool c = r.contains("contact");
    std::snprintf(b, sizeof b, "%s, realization %d, mu %.4g, A/A0 %.4f", r["label"].get<std::string>().c_str(),
                  r["realization"].get<int>(), c ? value_or_nan(r["contact"]["mu_peak"]) : NAN,
                  c ? value_or_nan(r["contact"]["area_at_peak"]) : NAN);
    return std::string(b);
  };
  k.table = roughness_table;
  k.extend = [spec](nlohmann::json& sweep) { sweep["thesis"] = thesis_rows(spec.dataset, spec.values); };
  k.plots = write_roughness_plots;
  k.print = print_roughness_table;
  return drive_sweep(c.common, k);
}

}  // namespace

Command add_sweep_coverage(CLI::App& root) {
  auto c = std::make_shared<CoverageCli>();
  CLI::App* s = root.add_subcommand("sweep-coverage", "friction against water coverage (thesis Figure 5.25)");
  s->footer(
      "For each coverage: fill the surface's pools (drained up to the surface's drained limit, standing\n"
      "water beyond it), use the wet surface as the rigid obstacle, run the shear test (Problem A then B,\n"
      "as `wetroad contact`), and record mu, A/A0, the pools' mean depth and the wet surface's PSD.\n"
      "Coverage 0 is the dry surface; mu_wet/mu_dry is taken per realization. Every finished run is\n"
      "checkpointed in OUT.runs/; --resume continues a killed sweep. Under mpirun the runs are shared\n"
      "among the ranks (each run on one rank); results do not depend on the rank count.\n"
      "Example: wetroad sweep-coverage --scene default --size 32 --dx 9.375e-4 --coverages 0 0.2 0.4 0.6 \\\n"
      "           --uz 1.5e-3 --ux 3e-3 --out sweep.h5 --csv sweep.csv --plots charts\n"
      "         mpirun -np 2 wetroad sweep-coverage --surface road.h5 --count 8 --uz 9e-3 --ux 3e-3 --out s.h5");
  s->add_option("--surface", c->surface, "surface file (HDF5 height map or text grid); or give synthesis options")->type_name("FILE");
  add_synth_options(*s, c->synth);
  s->add_option("--realizations", c->realizations, "independent synthetic surfaces (seeds seed, seed+1, ...)")
      ->capture_default_str();
  c->coverages_opt = s->add_option("--coverages", c->coverages, "target water coverages, fractions in [0, 1), ascending (0 = dry)")
      ->capture_default_str();
  c->count_opt = s->add_option("--count", c->count, "instead of --coverages: N+1 coverages evenly from 0 to --max-coverage");
  c->max_coverage_opt = s->add_option("--max-coverage", c->max_coverage, "largest coverage of --count")->capture_default_str();
  s->add_option("--tiling", c->tiling, "drainage: torus (exact periodic) or 3x3 (the thesis's tiling)")
      ->capture_default_str();
  s->add_option("--connectivity", c->connectivity, "4 or 8 neighbours for water flow")->capture_default_str();
  add_common_options(*s, c->common);
  return {s, [c] { return run_sweep_coverage(*c); }};
}

Command add_sweep_roughness(CLI::App& root) {
  auto c = std::make_shared<RoughnessCli>();
  c->common.sc.scene.normal_steps = 8;  // the normal curve's quartic fit needs points
  CLI::App* s = root.add_subcommand("sweep-roughness", "friction and contact area over h0, H or q1 (thesis Tables C.1, D.1-D.3)");
  s->footer(
      "The thesis's datasets (Table 5.1: 300 x 300 over 3 cm, q0 = 5 qL, H 0.7, h0 0.71 mm unless swept):\n"
      "  A: h0 = 10^-4.14 ... 10^-3.14 m;  B: H = 0.5 ... 0.9;  C: q1/q1hat = 1/8, 1/4, 1/2, 1.\n"
      "sampled as the thesis did (--sampling thesis: waves up to q1hat = 2 pi/dx, those above the grid's\n"
      "Nyquist aliased; --sampling nyquist gives band-limited surfaces, whose q1 is q1hat/2).\n"
      "Each value x each realization (seeds seed, seed+1, ...) is synthesized and sheared (Problem A in\n"
      "--steps normal steps, fitted by the quartic of eq. 5.4 for kappa, then Problem B). The table gives\n"
      "mean, 95 % CI and CoV of mu and A/A0 per value, beside the thesis's values (share/thesis/).\n"
      "Surface options (--size, --dx, ...) override the dataset's: a coarse grid makes a quick, cheaper run\n"
      "(its q1hat is then 2 pi over that grid's dx). Checkpointed and MPI-distributed as sweep-coverage.\n"
      "Example: wetroad sweep-roughness --dataset A --realizations 10 --uz 9e-3 --ux 3e-3 --refine 2 --out a.h5\n"
      "         wetroad sweep-roughness --dataset B --size 32 --dx 9.375e-4 --realizations 3 --uz 1.5e-3 \\\n"
      "           --ux 3e-3 --out b.h5 --plots b-charts");
  s->add_option("--dataset", c->dataset, "A (h0), B (H) or C (q1)")->capture_default_str();
  s->add_option("--values", c->values, "the swept parameter's values instead of the dataset's (h0 in m)");
  s->add_option("--realizations", c->realizations, "independent surfaces per value")->capture_default_str();
  add_synth_options(*s, c->synth);
  add_common_options(*s, c->common);
  return {s, [c] { return run_sweep_roughness(*c); }};
}

}  // namespace wr::app
