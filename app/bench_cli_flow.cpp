// `wetroad bench flow` and `wetroad bench percolation`: the CLI of bench/bench_flow.hpp.
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "app/bench_cli.hpp"
#include "bench/bench_flow.hpp"
#include "bench/bench_squeeze.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/io/atomic_output.hpp"
#include "reports/plot.hpp"

namespace wr::app {
namespace {

struct FlowBenchCli {
  std::vector<std::size_t> sizes = {256, 512, 1024};
  double sigma_star = 0.1;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string json;
};

int run_flow_bench(const FlowBenchCli& c) {
  int argc = 1;
  char name[] = "wetroad";
  char* args[] = {name, nullptr};
  char** argv = args;
  PetscSession petsc(&argc, &argv);  // the amg solver's PETSc
  std::fprintf(stderr, "thin-film flow: CHOLMOD against CG + GAMG\n");
  const nlohmann::json r = bench::flow_speed(c.sizes, c.sigma_star, c.seed, c.threads);
  std::printf("thin-film conductance of the elastic gap (half-space E 10 MPa, nu 0.45, sigma* %.3g; H 0.8, q1 = pi/(4 dx), "
              "seed %llu); solve = the whole conductance call after the contact solution\n",
              c.sigma_star, static_cast<unsigned long long>(c.seed));
  std::printf("  %6s %7s %9s %11s %12s %10s %10s %6s %11s %12s\n", "N", "A/A0", "contact s", "unknowns", "cholmod s",
              "amg s", "amg its", "", "max rel diff", "K_xx (m^3)");
  for (const auto& row : r["rows"])
    std::printf("  %6zu %7.4f %9.2f %11zu %12.3f %10.3f %10d %6s %11.2e %12.4e\n", row["n"].get<std::size_t>(),
                row["area_fraction"].get<double>(), row["contact_s"].get<double>(), row["unknowns"].get<std::size_t>(),
                row["cholmod"]["wall_s"].get<double>(), row["amg"]["wall_s"].get<double>(),
                row["amg"]["iterations"].get<int>(), "", row["max_relative_difference"].get<double>(),
                row["cholmod"]["kxx"].get<double>());
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

struct PercolationBenchCli {
  bench::PercolationSetup setup;
  std::string json, plot;
};

// The map's conductance (mean of K_xx and K_yy) and the effective medium's against A/A0, per
// ladder (logarithmic K; zeros are left out).
void write_ladder_plot(const std::string& path, const nlohmann::json& r) {
  PlotSpec p{"flow conductance against the contact area: the map (Reynolds) and the effective medium",
             "contact area fraction A/A0", "K (m^3)", false, true, {}};
  for (const auto& m : r["maps"]) {
    if (!m.contains("ladder")) continue;
    char h[32];
    std::snprintf(h, sizeof h, "H %.1f", m["hurst"].get<double>());
    PlotSeries map{std::string("map, ") + h, {}, {}, "linespoints", {}}, emt{std::string("effective medium, ") + h, {}, {}, "linespoints", {}};
    for (const auto& l : m["ladder"]) {
      const double a = l["area_fraction"].get<double>(), k = 0.5 * (l["kxx"].get<double>() + l["kyy"].get<double>());
      const double e = l["k_effective_medium"].get<double>();
      if (k > 0) map.x.push_back(a), map.y.push_back(k);
      if (e > 0) emt.x.push_back(a), emt.y.push_back(e);
    }
    p.series.push_back(map);
    p.series.push_back(emt);
  }
  write_svg_plot(path, p);
}

// "lo-hi" midpoint of a bracket [lo, hi].
double mid(const nlohmann::json& b) { return 0.5 * (b[0].get<double>() + b[1].get<double>()); }

int run_percolation_bench(const PercolationBenchCli& c) {
  const bench::PercolationSetup& st = c.setup;
  std::fprintf(stderr, "percolation of the free area: %zu maps of %zu^2\n", st.seeds.size() * st.hursts.size(), st.n);
  const nlohmann::json r = bench::percolation_threshold(st);
  std::printf("contact area fraction at which the free area (gap > 0, 4-connected) stops percolating; %zu^2, q0 = %.3g qL, "
              "q1 = 2 pi / (%.3g dx); elastic: half-space E 10 MPa nu 0.45 (bisection on the load), rigid: a flat cutting "
              "the map\n",
              st.n, st.q0_ratio, st.cells_per_wavelength);
  std::printf("  %6s %5s %11s %11s %11s %11s %7s\n", "seed", "H", "elastic x", "elastic y", "rigid x", "rigid y", "solves");
  double se = 0, sr = 0;
  std::map<double, std::pair<double, int>> by_h;
  for (const auto& m : r["maps"]) {
    const double ex = mid(m["elastic_x"]), ey = mid(m["elastic_y"]), rx = mid(m["rigid_x"]), ry = mid(m["rigid_y"]);
    std::printf("  %6llu %5.2f %11.4f %11.4f %11.4f %11.4f %7zu\n", m["seed"].get<unsigned long long>(),
                m["hurst"].get<double>(), ex, ey, rx, ry, m["contact_solves"].get<std::size_t>());
    se += ex + ey;
    sr += rx + ry;
    by_h[m["hurst"].get<double>()].first += ex + ey;
    by_h[m["hurst"].get<double>()].second += 2;
  }
  const double count = 2.0 * double(r["maps"].size());
  for (const auto& [h, s] : by_h) std::printf("  mean elastic A_c at H %.2f: %.4f\n", h, s.first / s.second);
  std::printf("  mean A_c: elastic %.4f (Dapp et al. 2012: about 0.42), rigid %.4f (0.5 for a symmetric field)\n",
              se / count, sr / count);
  for (const auto& m : r["maps"]) {
    if (!m.contains("ladder")) continue;
    std::printf("\n  conductance ladder, H %.2f seed %llu (K_xx, K_yy in m^3; flow factor K / (mean gap^3 / 12))\n",
                m["hurst"].get<double>(), m["seed"].get<unsigned long long>());
    std::printf("  %8s %10s %8s %12s %12s %12s %9s %9s %12s %9s %7s\n", "sigma*", "p (Pa)", "A/A0", "mean gap m", "K_xx", "K_yy",
                "phi_xx", "phi_yy", "K_eff.med.", "EM/map", "flow s");
    for (const auto& l : m["ladder"]) {
      const double u = l["mean_gap"].get<double>(), c3 = u * u * u / 12;
      const double km = 0.5 * (l["kxx"].get<double>() + l["kyy"].get<double>()), ke = l["k_effective_medium"].get<double>();
      std::printf("  %8.3f %10.4g %8.4f %12.4e %12.4e %12.4e %9.4f %9.4f %12.4e %9.3g %7.2f\n", l["sigma_star"].get<double>(),
                  l["pressure"].get<double>(), l["area_fraction"].get<double>(), u, l["kxx"].get<double>(),
                  l["kyy"].get<double>(), l["kxx"].get<double>() / c3, l["kyy"].get<double>() / c3, ke,
                  km > 0 ? ke / km : NAN, l["flow_s"].get<double>());
    }
  }
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  if (!c.plot.empty()) write_ladder_plot(c.plot, r);
  return 0;
}

struct SqueezeBenchCli {
  bench::SqueezeBenchSetup setup;
  std::string json;
};

int run_squeeze_bench(const SqueezeBenchCli& c) {
  const nlohmann::json r = bench::squeeze_rungs(c.setup);
  std::printf("squeeze-out of a %.3g mm film at %.3g MPa, elastic rubber E %.3g MPa: the mean field (Persson's load-separation,\n"
              "effective-medium flow) against the map (spectral contact's load-separation, Reynolds flow of its gap);\n"
              "times in ms to 1 %% and 90 %% asperity load, mean load share over %.3g ms\n",
              1e3 * c.setup.film, 1e-6 * c.setup.pressure, 1e-6 * c.setup.young, 1e3 * c.setup.patch_time);
  std::printf("  %8s %6s | %9s %9s %7s %9s %7s | %9s %9s %7s %9s %7s\n", "h0 mm", "L mm", "t1% mf", "t90% mf", "share",
              "u_eq um", "A_eq", "t1% map", "t90% map", "share", "u_eq um", "A_eq");
  auto ms = [](const nlohmann::json& t) { return t.is_null() ? INFINITY : 1e3 * t.get<double>(); };
  for (const auto& row : r["rows"]) {
    const auto &m = row["mean_field"], &p = row["map"];
    std::printf("  %8.3f %6.0f | %9.3g %9.3g %7.3f %9.1f %7.4f | %9.3g %9.3g %7.3f %9.1f %7.4f\n", 1e3 * row["h0"].get<double>(),
                1e3 * row["drainage_length"].get<double>(), ms(m["t_first_contact"]), ms(m["t_drained"]),
                m["load_share"].get<double>(), 1e6 * m["u_equilibrium"].get<double>(), m["area_equilibrium"].get<double>(),
                ms(p["t_first_contact"]), ms(p["t_drained"]), p["load_share"].get<double>(), 1e6 * p["u_equilibrium"].get<double>(),
                p["area_equilibrium"].get<double>());
  }
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

}  // namespace

BenchEntry add_squeeze_bench(CLI::App& bench) {
  auto o = std::make_shared<SqueezeBenchCli>();
  CLI::App* s = bench.add_subcommand("squeeze", "Squeeze-out of a film: the mean-field rung against the map (minute).");
  s->footer(
      "On default-scene surfaces (30 mm, H 0.7, q0 = 5 qL, q1 = Nyquist) of each --h0: the film's squeeze-out under a rib\n"
      "(lib/friction/squeeze_out.hpp) with the mean field the skid model runs on (Persson's load-separation and the\n"
      "effective medium, on the map's band) and with the map itself (the spectral half-space's mean gap, contact and\n"
      "the Reynolds conductance of its gap over a ladder of loads), for the same elastic rubber.\n"
      "Example: wetroad bench squeeze --h0 7.24e-5 3.02e-4");
  bench::SqueezeBenchSetup& st = o->setup;
  s->add_option("--h0", st.h0, "rms heights of the surfaces, m")->check(CLI::Range(1e-7, 1e-2))->capture_default_str();
  s->add_option("--size", st.n, "grid points per side")->check(CLI::Range(16, 4096))->capture_default_str();
  s->add_option("--seed", st.seed, "surface seed")->capture_default_str();
  s->add_option("--E", st.young, "Young's modulus of the rubber, Pa")->check(CLI::Range(1e3, 1e12))->capture_default_str();
  s->add_option("--pressure", st.pressure, "nominal pressure sigma0, Pa")->check(CLI::Range(1.0, 1e9))->capture_default_str();
  s->add_option("--film", st.film, "water film, m")->check(CLI::Range(1e-9, 1e-2))->capture_default_str();
  s->add_option("--threads", st.threads, "FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {s, [o] { return run_squeeze_bench(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_flow_bench(CLI::App& bench) {
  auto o = std::make_shared<FlowBenchCli>();
  CLI::App* s = bench.add_subcommand("flow", "Thin-film flow conductance on the map: CHOLMOD against CG + GAMG over grid sizes.");
  s->footer(
      "On a synthesized isotropic self-affine map per size: the spectral half-space contact at --sigma-star, then\n"
      "the Reynolds conductance tensor of its gap (lib/flow/thin_film_flow.hpp) by each solver, timed side by side.\n"
      "Example: wetroad bench flow --sizes 256 512 1024");
  s->add_option("--sizes", o->sizes, "grid sizes N (N x N maps)")->check(CLI::Range(4, 8192))->capture_default_str();
  s->add_option("--sigma-star", o->sigma_star, "normalised pressure sigma0 / (E* rms slope)")->check(CLI::PositiveNumber)->capture_default_str();
  s->add_option("--seed", o->seed, "surface seed")->capture_default_str();
  s->add_option("--threads", o->threads, "FFT threads of the contact solver (default: all cores)")->check(CLI::NonNegativeNumber);
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {s, [o] { return run_flow_bench(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_percolation_bench(CLI::App& bench) {
  auto o = std::make_shared<PercolationBenchCli>();
  CLI::App* s = bench.add_subcommand("percolation", "Contact area at which the free area stops percolating, elastic and rigid (minutes).");
  s->footer(
      "On isotropic self-affine maps: the elastic half-space's gap at increasing load, bisected on the load for the\n"
      "contact area fraction where the free area (gap > 0) stops winding around the torus in x and in y (Dapp,\n"
      "Luecke, Persson & Mueser, PRL 108, 244301 (2012): about 0.42); and a rigid flat cutting the map (0.5 for a\n"
      "field symmetric about its median). Then the conductance K_xx, K_yy over a ladder of loads.\n"
      "Example: wetroad bench percolation --size 512 --seeds 1 2 3 --hurst 0.3 0.8");
  bench::PercolationSetup& st = o->setup;
  s->add_option("--size", st.n, "grid points per side")->check(CLI::Range(8, 8192))->capture_default_str();
  s->add_option("--seeds", st.seeds, "surface seeds")->capture_default_str();
  s->add_option("--hurst", st.hursts, "Hurst exponents")->check(CLI::Range(0.0, 1.0))->capture_default_str();
  s->add_option("--q0-ratio", st.q0_ratio, "roll-off q0 / qL")->check(CLI::Range(1.0, 1e6))->capture_default_str();
  s->add_option("--cells-per-wavelength", st.cells_per_wavelength, "q1 = 2 pi / (this x dx); >= 2 (Nyquist)")
      ->check(CLI::Range(2.0, 1e6))->capture_default_str();
  s->add_option("--ladder", st.ladder, "sigma* of the conductance ladder")->check(CLI::PositiveNumber)->capture_default_str();
  s->add_option("--contact-tol", st.contact_tolerance, "the spectral solver's tolerance")->check(CLI::Range(1e-14, 1e-2))->capture_default_str();
  s->add_option("--threads", st.threads, "FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  s->add_option("--plot", o->plot, "chart the map's and the effective medium's conductance against A/A0 (SVG)")->type_name("OUTPUT");
  return {s, [o] { return run_percolation_bench(*o); }, &o->json, &o->plot, nullptr};
}

}  // namespace wr::app
