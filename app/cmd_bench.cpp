// `wetroad bench speed|summits`: benchmarks and long validations (bench/bench_harness.hpp).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "bench/bench_harness.hpp"
#include "lib/io/atomic_output.hpp"

namespace wr::app {
namespace {

struct BenchCli {
  std::vector<std::size_t> sizes = {300, 4096};
  int repeats = 3, threads = 0, realizations = 100;
  bool files = false;
  std::vector<double> fractions = {1.0, 0.5, 0.25, 0.125};
  std::string json;
};

int run_speed(const BenchCli& c) {
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

int run_summits(const BenchCli& c) {
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

}  // namespace

Command add_bench(CLI::App& root) {
  auto c = std::make_shared<BenchCli>();
  CLI::App* b = root.add_subcommand("bench", "benchmarks and long validations (not part of make test)");
  b->require_subcommand(1);
  CLI::App* sp = b->add_subcommand("speed", "Wall time and peak memory of synth + analyze on N x N surfaces.");
  sp->add_option("--sizes", c->sizes, "grid sizes N")->capture_default_str();
  sp->add_option("--repeat", c->repeats, "repetitions; the best time is reported")->capture_default_str();
  sp->add_option("--threads", c->threads, "worker threads (default: all hardware threads); results do not depend on it");
  sp->add_flag("--files", c->files, "go through an HDF5 file between synth and analyze (as the CLI does)");
  sp->add_option("--json", c->json, "write the results as JSON");
  CLI::App* su = b->add_subcommand("summits", "Summit-height statistics of surface ensembles against eq. 4.5 (Fig. 4.4).");
  su->add_option("--realizations", c->realizations, "surfaces per alpha")->capture_default_str();
  su->add_option("--fractions", c->fractions, "low-pass fractions q1/q1^ (dataset C)")->capture_default_str();
  su->add_option("--threads", c->threads, "worker threads (default: all hardware threads); results do not depend on it");
  su->add_option("--json", c->json, "write the results as JSON");
  return {b, [c, sp, su] {
            if (sp->parsed()) return run_speed(*c);
            if (su->parsed()) return run_summits(*c);
            return 2;
          }};
}

}  // namespace wr::app
