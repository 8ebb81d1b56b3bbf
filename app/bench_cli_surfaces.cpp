// `wetroad bench`: the surface, water and hysteresis benches; one options struct and one
// registration per bench.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/bench_cli.hpp"
#include "bench/bench_friction.hpp"
#include "bench/bench_harness.hpp"
#include "bench/bench_long_profile.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/provenance.hpp"
#include "lib/core/richardson.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "roads/surface_import.hpp"

namespace wr::app {
namespace {

struct SpeedBenchCli {
  bool files = false;
  std::string json;
  int repeats = 3;
  std::vector<std::size_t> sizes = {300, 4096};
  int threads = 0;
};

struct SummitsBenchCli {
  std::vector<double> fractions = {1.0, 0.5, 0.25, 0.125};
  std::string json;
  int realizations = 100;
  int threads = 0;
};

struct WaterBenchCli {
  std::string json;
  std::size_t water_n = 1024;
};

struct CoverageBenchCli {
  std::string json;
  int seeds = 10;
};

struct FrictionBenchCli {
  std::size_t friction_n = 4096;
  int friction_speeds = 30;
  std::string json;
  int repeats = 3;
  int threads = 0;
};

int run_speed(const SpeedBenchCli& c) {
  const auto rows = bench::speed(c.sizes, c.repeats, c.threads, c.files, std::filesystem::temp_directory_path());
  std::printf("synth + analyze, best of %d (in-process%s)\n", c.repeats, c.files ? ", through HDF5 files" : "");
  std::printf("  %6s %10s %10s %10s %10s %10s %12s %10s\n", "N", "synth [s]", "analyze", "write", "read", "total",
              "peak RSS", "RSS/map");
  for (const auto& r : rows) {
    if (r.contains("error")) {
      std::printf("  %6zu  error: %s\n", r["n"].get<std::size_t>(), r["error"].get<std::string>().c_str());
      continue;
    }
    std::printf("  %6zu %10.4f %10.4f %10.4f %10.4f %10.4f %9.1f MiB %10.2f\n", r["n"].get<std::size_t>(),
                r["synth_s"].get<double>(), r["analyze_s"].get<double>(), r["write_s"].get<double>(),
                r["read_s"].get<double>(), r["total_s"].get<double>(), r["peak_rss_bytes"].get<double>() / 1048576.0,
                r["peak_rss_over_map"].get<double>());
    std::printf("         analyze phases: %s\n", r["analyze_phases_s"].dump().c_str());
  }
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  return 0;
}

int run_summits(const SummitsBenchCli& c) {
  std::fprintf(stderr, "summit ensembles: %d surfaces per alpha (dataset C, 600x600 after 2x oversampling)\n",
               c.realizations);
  const auto rows = bench::summit_ensemble(c.fractions, c.realizations, c.threads);
  std::printf("summit heights xi = h/h0 against eq. 4.5 (thesis Fig. 4.4), ensemble means over surfaces\n");
  std::printf("  %7s %8s %8s | %8s %8s %8s | %8s %8s %8s | %7s\n", "q1/q1^", "alpha", "alpha_m", "mean",
              "eq4.5", "eq4.5(m)", "var", "eq4.5", "eq4.5(m)", "KS");
  for (const auto& r : rows)
    std::printf("  %7.4g %8.3f %8.3f | %8.4f %8.4f %8.4f | %8.4f %8.4f %8.4f | %7.4f\n", r["q1_fraction"].get<double>(),
                r["alpha_prescribed"].get<double>(), r["alpha_measured"].get<double>(), r["summit_mean"].get<double>(),
                r["eq45_mean"].get<double>(), r["eq45_mean_at_measured_alpha"].get<double>(),
                r["summit_var"].get<double>(), r["eq45_var"].get<double>(),
                r["eq45_var_at_measured_alpha"].get<double>(), r["ks_distance"].get<double>());
  std::printf("  (alpha: prescribed continuous PSD; alpha_m: measured on the lattice; (m): eq. 4.5 at alpha_m)\n");
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  return 0;
}

int run_water(const WaterBenchCli& c) {
  const auto r = bench::water_speed(c.water_n, 5);
  if (r.contains("error")) {
    std::printf("error: %s\n", r["error"].get<std::string>().c_str());
    return 1;
  }
  std::printf("water on a %zu x %zu default-like surface (serial code paths)\n", c.water_n, c.water_n);
  std::printf("  drained limit (direct)   %8.4f s  %6.2f Mcells/s\n", r["limit_s"].get<double>(),
              r["limit_cells_per_s"].get<double>() / 1e6);
  std::printf("  hierarchy build          %8.4f s  %6.2f Mcells/s  (%zu nodes)\n", r["hierarchy_s"].get<double>(),
              r["hierarchy_cells_per_s"].get<double>() / 1e6, r["hierarchy_nodes"].get<std::size_t>());
  std::printf("  further rain depth       %8.4f s mean, %.4f s worst  %6.2f Mcells/s\n", r["rain_mean_s"].get<double>(),
              r["rain_worst_s"].get<double>(), r["rain_cells_per_s"].get<double>() / 1e6);
  std::printf("  coverage target 30%%      %8.4f s (hierarchy + bisection)\n", r["coverage_target_s"].get<double>());
  std::printf("  peak memory              %8.1f MiB (%.1f bytes per cell)\n", r["peak_rss_bytes"].get<double>() / 1048576,
              r["peak_rss_bytes"].get<double>() / double(c.water_n * c.water_n));
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

int run_coverage(const CoverageBenchCli& c) {
  const auto rows = bench::water_limit_coverage(c.seeds);
  std::printf("drained-limit coverage of the default surface (300x300, h0 0.3 mm, H 0.7), %d seeds; thesis: 40.45%%\n",
              c.seeds);
  std::printf("  %12s %20s %20s %16s\n", "connectivity", "exact torus", "3x3 tiling", "cells differing");
  for (const auto& r : rows)
    std::printf("  %12d %12.2f +- %4.2f %12.2f +- %4.2f %16.0f\n", r["connectivity"].get<int>(),
                100 * r["exact_mean"].get<double>(), 100 * r["exact_std"].get<double>(),
                100 * r["tiled_3x3_mean"].get<double>(), 100 * r["tiled_3x3_std"].get<double>(),
                r["tiling_differing_cells_mean"].get<double>());
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  return 0;
}

int run_friction(const FrictionBenchCli& c) {
  const auto r = bench::friction_speed(c.friction_n, c.friction_speeds, c.repeats, c.threads);
  std::printf("hysteresis friction on a %zu x %zu default-like surface, %d speeds 1e-6 ... 100 m/s, %s threads\n",
              c.friction_n, c.friction_n, c.friction_speeds, c.threads > 0 ? std::to_string(c.threads).c_str() : "all");
  std::printf("  spectrum (FFT, radial PSD, fit)   %8.4f s\n", r["psd_seconds"].get<double>());
  std::printf("  mu(v), isothermal                 %8.4f s  (peak mu %.4f)\n", r["curve_seconds"].get<double>(),
              r["peak_mu_isothermal"].get<double>());
  std::printf("  mu(v), flash temperature          %8.4f s  (peak mu %.4f)\n", r["curve_flash_seconds"].get<double>(),
              r["peak_mu_flash"].get<double>());
  std::printf("  mu(v) under the E274 film, with flash temperature, its 17 skid speeds, Sp and hydroplaning speed\n"
              "    (mu_h included)                 %8.4f s  (SN %.1f, Sp %s km/h)\n",
              r["film_seconds"].get<double>(), r["film_sn"].get<double>(),
              r["film_sp_kmh"].is_null() ? "none" : std::to_string(std::lround(r["film_sp_kmh"].get<double>())).c_str());
  std::printf("  speed against accuracy (isothermal; error against 400 points per decade):\n");
  std::printf("    %18s %10s %18s\n", "points per decade", "seconds", "max rel. error");
  for (const auto& row : r["accuracy_ladder"])
    std::printf("    %18d %10.5f %18.2e\n", row["points_per_decade"].get<int>(), row["seconds"].get<double>(),
                row["max_relative_error"].get<double>());
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

struct LongProfileBenchCli {
  bench::LongProfileOptions o;
  std::string json;
};

int run_long_profile(LongProfileBenchCli& c) {
  if (c.o.samples < 1000 || c.o.samples > 2'000'000'000) throw InputError("--samples", "must be 1000 ... 2e9");
  if (!(c.o.dx > 0 && c.o.dx < 1)) throw InputError("--dx", "must be a spacing in m, 0 < dx < 1");
  if (!(c.o.evaluation_length >= 0 && std::isfinite(c.o.evaluation_length)))
    throw InputError("--evaluation-length", "must be a length >= 0 in m");
  if (!(c.o.dropout_share >= 0 && c.o.dropout_share <= 0.5)) throw InputError("--dropouts", "must be a share 0 ... 0.5");
  if (!(c.o.spike_rate >= 0 && c.o.spike_rate <= 0.1)) throw InputError("--spikes", "must be a rate 0 ... 0.1 per sample");
  c.o.scratch_dir = std::filesystem::temp_directory_path().string();
  const nlohmann::json r = bench::long_profile(c.o);
  if (r.contains("error")) throw InputError("bench long-profile", r["error"].get<std::string>());
  std::printf("analyze of a continuous record: %zu samples at %.3g mm (%.4g km), %zu dropouts, %zu spikes added\n",
              c.o.samples, c.o.dx * 1e3, r["length_m"].get<double>() / 1e3, r["dropouts"].get<std::size_t>(),
              r["spikes_added"].get<std::size_t>());
  std::printf("  synthesize %.2f s, write HDF5 %.2f s (not counted)\n", r["synth_s"].get<double>(), r["write_s"].get<double>());
  std::printf("  read %.2f s + analyze %.2f s = %.2f s wall; peak RSS %.0f MiB (%.1f x the profile's %.0f MiB)\n",
              r["read_s"].get<double>(), r["analyze_s"].get<double>(), r["total_s"].get<double>(),
              r["peak_rss_bytes"].get<double>() / 1048576.0,
              r["peak_rss_bytes"].get<double>() / r["profile_bytes"].get<double>(), r["profile_bytes"].get<double>() / 1048576.0);
  std::printf("  analyze phases [s]: %s\n", r["phases_s"].dump().c_str());
  std::printf("  MPD %.4g mm (%zu/%zu valid segments, %zu spike samples); per %.4g m: %zu counted of %zu, "
              "mean %.4g mm, min %.4g, max %.4g\n",
              r["mpd"].get<double>() * 1e3, r["valid_segments"].get<std::size_t>(), r["segments"].get<std::size_t>(),
              r["spike_samples"].get<std::size_t>(), c.o.evaluation_length, r["evaluations_counted"].get<std::size_t>(),
              r["evaluations"].get<std::size_t>(), r["evaluation_mean"].is_number() ? r["evaluation_mean"].get<double>() * 1e3 : NAN,
              r["evaluation_min"].is_number() ? r["evaluation_min"].get<double>() * 1e3 : NAN,
              r["evaluation_max"].is_number() ? r["evaluation_max"].get<double>() * 1e3 : NAN);
  std::printf("  PSD: %zu bins, %zu of them fitted\n", r["psd_bins"].get<std::size_t>(), r["psd_fit_bins"].get<std::size_t>());
  if (!c.o.file.empty()) std::printf("  record kept: %s\n", c.o.file.c_str());
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

}  // namespace

BenchEntry add_long_profile_bench(CLI::App& bench) {
  auto c = std::make_shared<LongProfileBenchCli>();
  CLI::App* s = bench.add_subcommand("long-profile",
                                     "analyze of a long continuous texture record (default 10 km at 0.5 mm) with dropouts "
                                     "and spikes: wall time and peak memory");
  s->footer(
      "Synthesizes a road-like record (macrotexture, megatexture, a grade wave; dropouts in bursts as NaN and\n"
      "spikes of 5-30 mm), writes it as an HDF5 /profile, then reads and analyzes it in a fresh process as\n"
      "`wetroad analyze FILE` does (continuous MPD, MPD per evaluation length). Peak RSS is that process's.\n"
      "Example: wetroad bench long-profile --samples 20000000 --file big.h5   (then time `wetroad analyze big.h5`)");
  s->add_option("--samples", c->o.samples, "samples in the record")->check(CLI::Range(8, 1000000000))->capture_default_str();
  s->add_option("--dx", c->o.dx, "sample spacing in m")->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  s->add_option("--evaluation-length", c->o.evaluation_length, "MPD evaluation length in m (0 = off)")->capture_default_str();
  s->add_option("--dropouts", c->o.dropout_share, "share of samples that are dropouts")->check(CLI::Range(0.0, 0.5))->capture_default_str();
  s->add_option("--spikes", c->o.spike_rate, "spikes per sample")->check(CLI::Range(0.0, 0.1))->capture_default_str();
  s->add_option("--seed", c->o.seed, "random seed")->capture_default_str();
  s->add_option("--threads", c->o.threads, "worker threads (default: all hardware threads)")->check(CLI::NonNegativeNumber);
  s->add_option("--file", c->o.file, "write the record here and keep it (default: a temporary file, removed)")->type_name("OUTPUT");
  s->add_option("--json", c->json, "write the results as JSON")->type_name("OUTPUT");
  return {s, [c] { return run_long_profile(*c); }, &c->json, nullptr, nullptr};
}

BenchEntry add_speed_bench(CLI::App& bench) {
  auto o = std::make_shared<SpeedBenchCli>();
  CLI::App* sp = bench.add_subcommand("speed", "Wall time and peak memory of synth + analyze on N x N surfaces.");
  sp->add_option("--sizes", o->sizes, "grid sizes N")->check(CLI::Range(2, 65536))->capture_default_str();
  sp->add_option("--repeat", o->repeats, "repetitions; the best time is reported")->check(CLI::Range(1, 1000000))->capture_default_str();
  sp->add_option("--threads", o->threads, "worker threads (default: all hardware threads); results do not depend on it")->check(CLI::NonNegativeNumber);
  sp->add_flag("--files", o->files, "go through an HDF5 file between synth and analyze (as the CLI does)");
  sp->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {sp, [o] { return run_speed(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_summits_bench(CLI::App& bench) {
  auto o = std::make_shared<SummitsBenchCli>();
  CLI::App* su = bench.add_subcommand("summits", "Summit-height statistics of surface ensembles against eq. 4.5 (Fig. 4.4).");
  su->add_option("--realizations", o->realizations, "surfaces per alpha")->check(CLI::Range(1, 1000000))->capture_default_str();
  su->add_option("--fractions", o->fractions, "low-pass fractions q1/q1^ (dataset C)")->capture_default_str();
  su->add_option("--threads", o->threads, "worker threads (default: all hardware threads); results do not depend on it")->check(CLI::NonNegativeNumber);
  su->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {su, [o] { return run_summits(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_water_bench(CLI::App& bench) {
  auto o = std::make_shared<WaterBenchCli>();
  CLI::App* wa = bench.add_subcommand("water", "Speed and memory of the water module (drained limit, hierarchy, rain depths).");
  wa->add_option("--size", o->water_n, "grid size N")->check(CLI::Range(2, 65536))->capture_default_str();
  wa->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {wa, [o] { return run_water(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_coverage_bench(CLI::App& bench) {
  auto o = std::make_shared<CoverageBenchCli>();
  CLI::App* co = bench.add_subcommand("coverage", "Drained-limit coverage of the default surface over seeds (4 and 8 connectivity).");
  co->add_option("--seeds", o->seeds, "realizations")->check(CLI::Range(1, 1000000))->capture_default_str();
  co->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {co, [o] { return run_coverage(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_friction_bench(CLI::App& bench) {
  auto o = std::make_shared<FrictionBenchCli>();
  CLI::App* fr = bench.add_subcommand("friction", "Speed and accuracy of the hysteresis model: mu at S speeds from an N x N PSD.");
  fr->add_option("--size", o->friction_n, "grid size N")->check(CLI::Range(2, 65536))->capture_default_str();
  fr->add_option("--speeds", o->friction_speeds, "number of speeds")->check(CLI::Range(1, 1000000))->capture_default_str();
  fr->add_option("--repeat", o->repeats, "repetitions; the best time is reported")->check(CLI::Range(1, 1000000))->capture_default_str();
  fr->add_option("--threads", o->threads, "worker threads (default: all hardware threads)")->check(CLI::NonNegativeNumber);
  fr->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {fr, [o] { return run_friction(*o); }, &o->json, nullptr, nullptr};
}

}  // namespace wr::app
