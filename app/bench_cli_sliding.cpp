// `wetroad bench sliding` and `wetroad bench sliding-convergence`: the CLI of bench/bench_sliding.hpp.
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/bench_cli.hpp"
#include "lib/core/errors.hpp"
#include "bench/bench_sliding.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/input_file.hpp"
#include "reports/plot.hpp"

namespace wr::app {
namespace {

struct SlidingBenchCli {
  bench::SlidingBenchSetup setup;
  std::string json, plot, plot_ratio;
};

void add_scene_options(CLI::App* s, bench::SlidingBenchSetup& st) {
  s->add_option("--band", st.band, "q1 / qL: the shortest wavelength is the tile / band")->check(CLI::Range(4.0, 1e5))->capture_default_str();
  s->add_option("--h0", st.h0, "rms height, m")->check(CLI::Range(1e-7, 1e-2))->capture_default_str();
  s->add_option("--pressures", st.pressures, "nominal pressures sigma0, Pa")->check(CLI::Range(1.0, 1e9))->capture_default_str();
  s->add_option("--temperature", st.temperature, "deg C")->capture_default_str();
  s->add_option("--tolerance", st.tolerance, "the solver's relative change per iteration")->check(CLI::Range(1e-14, 1e-2))->capture_default_str();
  s->add_option("--compound", st.compound, "compound JSON (default: the synthetic tread)")->type_name("FILE");
  s->add_option("--threads", st.threads, "FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
}

// mu(v) of both models per pressure (means over the seeds), or Persson / exact.
void write_charts(const SlidingBenchCli& c, const nlohmann::json& r) {
  PlotSpec mu{"hysteresis friction: exact steady sliding on the map and Persson's theory on its spectrum",
              "sliding speed v (m/s)", "friction coefficient", true, false, {}};
  PlotSpec ratio{"Persson's theory / exact steady sliding (same maps, same band)", "sliding speed v (m/s)",
                 "ratio", true, false, {}};
  for (double p : c.setup.pressures) {
    char tag[48];
    std::snprintf(tag, sizeof tag, "sigma0 %.2g MPa", p / 1e6);
    PlotSeries ex{std::string("exact, ") + tag, {}, {}, "linespoints", {}}, pe{std::string("Persson, ") + tag, {}, {}, "lines", {}};
    PlotSeries rm{std::string("mu, ") + tag, {}, {}, "linespoints", {}}, ra{std::string("A/A0, ") + tag, {}, {}, "linespoints", {}};
    for (const auto& s : r["summary"]) {
      if (s["pressure"].get<double>() != p) continue;
      const double v = s["v"].get<double>();
      ex.x.push_back(v), ex.y.push_back(s["mu"].get<double>());
      pe.x.push_back(v), pe.y.push_back(s["mu_persson"].get<double>());
      rm.x.push_back(v), rm.y.push_back(s["ratio"].get<double>());
      ra.x.push_back(v), ra.y.push_back(s["area_ratio"].get<double>());
    }
    mu.series.insert(mu.series.end(), {ex, pe});
    ratio.series.insert(ratio.series.end(), {rm, ra});
  }
  if (!c.plot.empty()) write_svg_plot(c.plot, mu);
  if (!c.plot_ratio.empty()) write_svg_plot(c.plot_ratio, ratio);
}

int run_sliding_bench(const SlidingBenchCli& c) {
  const bench::SlidingBenchSetup& st = c.setup;
  std::fprintf(stderr, "steady viscoelastic sliding against Persson's theory: %zu maps of %zu^2, band q1 = %g qL\n",
               st.seeds.size(), st.n, st.band);
  const nlohmann::json r = bench::sliding_against_persson(st);
  std::printf("exact steady sliding (lib/spectral/viscoelastic_sliding) against Persson's theory on the same maps' spectra\n"
              "(30 mm tile, h0 %.3g m, H 0.7, q0 = 5 qL, q1 = %g qL, %zu^2, %zu seeds, %g C, isothermal); means over the seeds\n",
              st.h0, st.band, st.n, st.seeds.size(), st.temperature);
  std::printf("  %10s %10s %9s %9s %7s %9s %9s %7s %8s\n", "sigma0 Pa", "v m/s", "mu exact", "Persson", "ratio", "A exact",
              "A Persson", "ratio", "s/speed");
  for (const auto& s : r["summary"]) {
    const double ratio = s["ratio"].get<double>();
    std::printf("  %10.3g %10.3g %9.4f %9.4f %7.3f %9.5f %9.5f %7.3f %8.2f%s\n", s["pressure"].get<double>(), s["v"].get<double>(),
                s["mu"].get<double>(), s["mu_persson"].get<double>(), ratio, s["area_fraction"].get<double>(),
                s["area_persson"].get<double>(), s["area_ratio"].get<double>(), s["wall_s"].get<double>(),
                std::abs(ratio - 1) > 0.2 ? "  > 20 %" : "");
  }
  std::printf("solver arrays %.1f MiB, peak memory %.1f MiB\n", r["memory_bytes"].get<double>() / 1048576.0,
              r["peak_rss_bytes"].get<double>() / 1048576.0);
  write_charts(c, r);
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

struct ConvergenceCli {
  bench::SlidingBenchSetup setup;
  std::vector<std::size_t> sizes = {256, 512, 1024};
  std::vector<double> speeds = {1e-4, 1e-2, 1.0};
  std::string json, ladder_plot, fem_json;
};

// The friction ladder's speed against accuracy: wall time per speed against the relative error to
// the grid-converged exact friction (Richardson's limit), for Persson's theory and the exact rung
// on each grid; the FEM's elastostatic friction (another mechanism) against its own mesh limit
// from `bench mesh-convergence --json`.
void write_ladder_plot(const std::string& path, const nlohmann::json& r, const std::string& fem_json) {
  PlotSpec p{"friction ladder: time per speed against the error to the converged answer", "wall time per speed (s)",
             "relative error", true, true, {}};
  p.key = "bottom left";
  std::vector<double> limits;
  for (const auto& e : r["estimates"]) limits.push_back(e.contains("limit") && !e["limit"].is_null() ? e["limit"].get<double>() : 0.0);
  PlotSeries persson{"Persson's theory, each speed", {}, {}, "points", {}};
  for (std::size_t i = 0; i < limits.size(); ++i)
    if (limits[i] > 0) {
      persson.x.push_back(r["persson"][i]["wall_s"].get<double>());
      persson.y.push_back(std::abs(r["persson"][i]["mu"].get<double>() / limits[i] - 1));
    }
  p.series.push_back(persson);
  for (std::size_t i = 0; i < limits.size(); ++i) {
    if (limits[i] <= 0) continue;
    char label[80];
    std::snprintf(label, sizeof label, "exact, v %.3g m/s (%zu^2 ... %zu^2)", r["estimates"][i]["v"].get<double>(),
                  r["grids"].front()["n"].get<std::size_t>(), r["grids"].back()["n"].get<std::size_t>());
    PlotSeries ex{label, {}, {}, "linespoints", {}};
    for (const auto& g : r["grids"]) {
      const auto& pt = g["points"][i];
      const double err = std::abs(pt["mu"].get<double>() / limits[i] - 1);
      if (err <= 0) continue;
      ex.x.push_back(pt["wall_s"].get<double>());
      ex.y.push_back(err);
    }
    p.series.push_back(ex);
  }
  if (!fem_json.empty()) {
    nlohmann::json f;
    try {
      f = nlohmann::json::parse(read_input_file(fem_json, "FEM mesh-convergence JSON"));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fem_json, std::string("not the JSON of `bench mesh-convergence`: ") + e.what());
    }
    if (!f.contains("meshes") || !f.contains("extrapolations"))
      throw InputError(fem_json, "not the JSON of `bench mesh-convergence` (no meshes and extrapolations)");
    double limit = 0;
    for (const auto& e : f["extrapolations"])
      if (e.contains("mu") && e["mu"].contains("limit")) limit = e["mu"]["limit"].get<double>();
    PlotSeries fem{"FEM elastostatic mu (a shear test), to its mesh limit", {}, {}, "linespoints", {}};
    for (const auto& m : f["meshes"])
      if (limit > 0 && m.contains("mu") && m.contains("wall_s")) {
        fem.x.push_back(m["wall_s"].get<double>());
        fem.y.push_back(std::max(std::abs(m["mu"].get<double>() / limit - 1), 1e-6));
      }
    if (!fem.x.empty()) p.series.push_back(fem);
  }
  write_svg_plot(path, p);
}

int run_convergence_bench(const ConvergenceCli& c) {
  for (std::size_t k = 0; k < c.sizes.size(); ++k)
    if (c.sizes[k] % c.sizes.front() != 0 || (k > 0 && c.sizes[k] <= c.sizes[k - 1]))
      throw InputError("--sizes", "give ascending sizes, each a multiple of the first (the same surface, refined)");
  if (double(c.sizes.front()) < 2 * c.setup.band)
    throw InputError("--sizes", "the first grid must resolve the band: at least 2 x --band points per side");
  std::fprintf(stderr, "steady viscoelastic sliding: grid convergence on one band\n");
  const nlohmann::json r = bench::sliding_grid_convergence(c.setup, c.sizes, c.speeds);
  std::printf("grid convergence of the exact rung (band q1 = %g qL, seed %llu, sigma0 %.3g Pa)\n", c.setup.band,
              static_cast<unsigned long long>(r["seed"].get<std::uint64_t>()), r["pressure"].get<double>());
  for (const auto& e : r["estimates"]) {
    std::printf("  v %8.3g m/s  mu:", e["v"].get<double>());
    for (const auto& m : e["mu"]) std::printf(" %.5f", m.get<double>());
    if (e.contains("limit") && !e["limit"].is_null())
      std::printf("  -> limit %.5f, order %.2f, GCI %.2f %%", e["limit"].get<double>(), e["order"].get<double>(),
                  100 * e["relative_error"].get<double>());
    else if (e.contains("note"))
      std::printf("  (%s)", e["note"].get<std::string>().c_str());
    if (e.contains("finest_change")) std::printf("  last refinement changed mu by %.2f %%", 100 * e["finest_change"].get<double>());
    std::printf("\n");
  }
  std::printf("  Persson's theory on the same band:");
  for (const auto& q : r["persson"]) std::printf(" v %.3g: %.5f (%.2g s)", q["v"].get<double>(), q["mu"].get<double>(), q["wall_s"].get<double>());
  std::printf("\n");
  if (!c.ladder_plot.empty()) write_ladder_plot(c.ladder_plot, r, c.fem_json);
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

}  // namespace

BenchEntry add_sliding_bench(CLI::App& bench) {
  auto o = std::make_shared<SlidingBenchCli>();
  CLI::App* s = bench.add_subcommand("sliding", "Exact steady viscoelastic sliding against Persson's theory on the same maps (minutes).");
  s->footer(
      "On default-scene surfaces band-limited to q1 = --band qL (30 mm tile, h0 0.3 mm, H 0.7, q0 = 5 qL): the steady\n"
      "sliding of the compound's half-space over each map (lib/spectral/viscoelastic_sliding.hpp) and Persson's mu(v)\n"
      "and A/A0 from the map's radial PSD on the same band, per seed, pressure and speed; the time per speed and the\n"
      "solver's memory. The JSON splits each friction by octaves of q (bands) for both models.\n"
      "Example: wetroad bench sliding --size 512 --seeds 1 2 3 --pressures 1e5 3e5 --plot mu.svg --plot-ratio ratio.svg");
  bench::SlidingBenchSetup& st = o->setup;
  s->add_option("--size", st.n, "grid points per side")->check(CLI::Range(16, 8192))->capture_default_str();
  s->add_option("--seeds", st.seeds, "surface seeds")->capture_default_str();
  s->add_option("--speed-range", st.speed_min, "lowest speed, m/s")->check(CLI::Range(1e-12, 1e3))->capture_default_str();
  s->add_option("--speed-max", st.speed_max, "highest speed, m/s")->check(CLI::Range(1e-12, 1e3))->capture_default_str();
  s->add_option("--per-decade", st.per_decade, "speeds per decade")->check(CLI::Range(1, 20))->capture_default_str();
  add_scene_options(s, st);
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  s->add_option("--plot", o->plot, "chart mu(v) of both models (SVG)")->type_name("OUTPUT");
  s->add_option("--plot-ratio", o->plot_ratio, "chart Persson / exact for mu and A/A0 against v (SVG)")->type_name("OUTPUT");
  return {s, [o] { return run_sliding_bench(*o); }, &o->json, &o->plot, nullptr, {{"--plot-ratio", &o->plot_ratio}}};
}

BenchEntry add_sliding_convergence_bench(CLI::App& bench) {
  auto o = std::make_shared<ConvergenceCli>();
  CLI::App* s = bench.add_subcommand("sliding-convergence", "Grid convergence of exact steady sliding: one band on finer grids (minutes).");
  s->footer(
      "The same band-limited surface (one seed) on grids of --sizes points per side, mu at --speeds, and Richardson's\n"
      "extrapolation with the observed order and the GCI from the three finest.\n"
      "Example: wetroad bench sliding-convergence --sizes 512 1024 2048 --band 64");
  bench::SlidingBenchSetup& st = o->setup;
  st.seeds = {1};
  st.pressures = {0.3e6};
  s->add_option("--sizes", o->sizes, "grid sizes, each the double of the one before")->check(CLI::Range(16, 8192))->capture_default_str();
  s->add_option("--speeds", o->speeds, "sliding speeds, m/s")->check(CLI::Range(1e-12, 1e3))->capture_default_str();
  s->add_option("--seed", st.seeds.front(), "surface seed")->capture_default_str();
  add_scene_options(s, st);
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  s->add_option("--ladder-plot", o->ladder_plot,
                "chart the friction ladder's time per speed against the error to the converged exact mu (SVG)")
      ->type_name("OUTPUT");
  s->add_option("--fem-json", o->fem_json, "the FEM's elastostatic series for the ladder chart: `bench mesh-convergence --json`")
      ->type_name("FILE");
  return {s, [o] { return run_convergence_bench(*o); }, &o->json, &o->ladder_plot, &o->fem_json};
}

}  // namespace wr::app
