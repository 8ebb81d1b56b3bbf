// `wetroad bench`: the contact-model benches (spectral, FEM, both); one options struct and one
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

struct SpectralSpeedBenchCli {
  int admit_every = 8;
  std::string json;
  int spectral_loads = 10;
  std::vector<std::size_t> spectral_sizes = {1024, 2048};
  double spectral_tol = 1e-8;
  int threads = 0;
};

struct SpectralShearBenchCli {
  std::string json;
  std::size_t shear_n = 512;
  int shear_steps = 4;
  double shear_ux = 2e-5;
  double shear_uz = 5e-5;
  double spectral_tol = 1e-8;
  int threads = 0;
};

struct KappaBenchCli {
  std::string json;
  std::size_t kappa_band = 256;
  int kappa_seeds = 4;
  std::vector<std::size_t> kappa_sizes = {256, 512, 1024};
  bool period_effect = false;
  std::string plot;  // SVG chart, where a bench draws one
  int threads = 0;
};

struct SpectralVsFemBenchCli {
  std::vector<double> compare_h0 = {1.5e-5, 3e-5, 6e-5, 1e-4, 2e-4};
  int compare_refine = 1;
  std::string json;
  std::string plot;  // SVG chart, where a bench draws one
};

struct AccuracyBenchCli {
  double accuracy_h0 = 3e-5;
  std::vector<int> fem_refines = {1, 2};
  std::string json;
  std::string plot;  // SVG chart, where a bench draws one
  std::vector<int> spectral_refines = {1, 2, 4, 8};
};

struct MeshConvergenceBenchCli {
  std::string json;
  double mc_nu = 0.45;
  std::vector<int> mc_refines = {1, 2, 4, 8};
  int mc_shear_steps = 3;
  int mc_steps = 2;
  std::string mc_surface;
  double mc_tol = 1e-3;
  double mc_ux = 3e-3;
  double mc_uz = 1.5e-3;
  std::string plot;  // SVG chart, where a bench draws one
};

struct HertzBenchCli {
  int hertz_layers = 8;
  std::vector<int> hertz_meshes = {32, 64, 128};
  double hertz_radius = 0.1;
  double hertz_uz = 6e-5;
  std::string json;
};

struct SpotBenchCli {
  std::string json;
  int spot_layers = 4;
  std::vector<int> spot_refines = {1, 2};
  std::vector<int> spot_sizes = {1, 2, 4};
};

// PETSc and MPI for the benches that run the FEM (mpirun -np N ok), with this process's rank.
struct FemBenchSession {
  int argc = 1;
  char name[8] = "wetroad";
  char* args[2] = {name, nullptr};
  char** argv = args;
  PetscSession petsc{&argc, &argv};
  int rank = rank_of_world();
  static int rank_of_world() {
    int r = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &r);
    return r;
  }
};

int session_size() {
  int n = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &n);
  return n;
}

int run_spectral_speed(const SpectralSpeedBenchCli& c) {
  std::fprintf(stderr, "spectral normal contact: %d loads per surface\n", c.spectral_loads);
  const auto rows = bench::spectral_speed(c.spectral_sizes, c.spectral_loads, c.threads, c.spectral_tol, c.admit_every);
  std::printf("spectral normal contact (half-space, load control, sigma* = 0.01 ... %.2f, warm starts, tol %.0e, "
              "CG in %s precision, admissions every %d)\n", 0.01 * c.spectral_loads, c.spectral_tol,
              rows.empty() ? "-" : rows[0]["cg_precision"].get<std::string>().c_str(), c.admit_every);
  std::printf("  %6s %8s %9s %10s %10s %8s %8s %12s %12s %10s\n", "N", "threads", "plan [s]", "setup [s]",
              "solve [s]", "iters", "pairs", "s/iteration", "FFT pair [s]", "A/A0 last");
  for (const auto& r : rows)
    std::printf("  %6zu %8d %9.3f %10.3f %10.3f %8d %8d %12.4g %12.4g %10.4f%s\n", r["n"].get<std::size_t>(),
                r["threads"].get<int>(), r["planning_s"].get<double>(), r["setup_s"].get<double>(),
                r["solve_s"].get<double>(), r["iterations"].get<int>(), r["fft_pairs"].get<int>(),
                r["s_per_iteration"].get<double>(), r["fft_pair_s"].get<double>(),
                r["steps"].back()["area_fraction"].get<double>(), r["converged"].get<bool>() ? "" : "  NOT CONVERGED");
  std::printf("  (plan: measuring the FFT plans, paid once per machine and size: they are cached in %s;\n"
              "   pairs: convolutions, each a forward and a backward FFT; the rest of an iteration is vector work)\n",
              fft_wisdom_path().c_str());
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  return 0;
}

int run_spectral_shear(const SpectralShearBenchCli& c) {
  const auto r = bench::spectral_shear(c.shear_n, c.shear_uz, c.shear_ux, c.shear_steps, c.threads, c.spectral_tol);
  std::printf("spectral shear test on %zu^2 (layer %.3g m thick over a 1 cm period, rms slope %.3f; uz %.3g m then "
              "ux %.3g m, %d steps each; tol %.0e, CG in %s precision)\n",
              c.shear_n, r["thickness"].get<double>(), r["rms_slope"].get<double>(), c.shear_uz, c.shear_ux,
              c.shear_steps, c.spectral_tol, r["cg_precision"].get<std::string>().c_str());
  std::printf("  %4s %10s %10s %8s %9s %9s %8s %9s\n", "step", "uz [m]", "ux [m]", "A/A0", "mu", "geometry", "CG",
              "wall [s]");
  int k = 0;
  for (const auto& s : r["steps"])
    std::printf("  %4d %10.4g %10.4g %8.4f %9.2e %9d %8d %9.3f%s\n", ++k, s["uz"].get<double>(), s["ux"].get<double>(),
                s["area_fraction"].get<double>(), s["mu"].get<double>(), s["geometry_iterations"].get<int>(),
                s["cg_iterations"].get<int>(), s["wall_s"].get<double>(), s["converged"].get<bool>() ? "" : "  NOT CONVERGED");
  std::printf("  total %.2f s (setup %.2f s), %d geometry and %d CG iterations, %d threads; FFT pair %.4g s "
              "(planning %.2f s, cached)\n",
              r["wall_s"].get<double>(), r["setup_s"].get<double>(), r["geometry_iterations"].get<int>(),
              r["cg_iterations"].get<int>(), r["threads"].get<int>(), r["fft_pair_s"].get<double>(),
              r["planning_s"].get<double>());
  std::printf("  (mu of a periodic layer is 0 up to lattice effects: this measures speed, not friction)\n");
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return r["converged"].get<bool>() ? 0 : 1;
}

int run_kappa(const KappaBenchCli& c) {
  const auto rows = bench::spectral_kappa(c.kappa_sizes, c.kappa_band, c.kappa_seeds, c.threads, c.period_effect);
  if (c.period_effect)
    std::printf("spectral half-space, period effect: the spacing of %zu^2 over 1 cm kept, the period growing with N\n"
                "(H 0.7, q0 = 5 qL, q1 = Nyquist); %d seeds. kappa = A/A0 / sigma* at sigma* = 0.005 (Persson 1.596, "
                "BGT 2.507)\n", c.kappa_sizes.front(), c.kappa_seeds);
  else
    std::printf("spectral half-space on one band-limited surface per seed (H 0.7, q0 = 5 qL, q1 = Nyquist of %zu^2),\n"
                "sampled on finer grids; %d seeds. kappa = A/A0 / sigma* at sigma* = 0.005 (Persson 1.596, BGT 2.507)\n",
                c.kappa_band, c.kappa_seeds);
  std::printf("  %6s %8s", "N", "kappa");
  for (const auto& p : rows[0]["curve"]) std::printf("  A(%.3g)", p["sigma_star"].get<double>());
  std::printf(" %8s\n", "wall s");
  for (const auto& r : rows) {
    std::printf("  %6zu %8.4f", r["n"].get<std::size_t>(), r["kappa"].get<double>());
    for (const auto& p : r["curve"]) std::printf("  %7.5f", p["area_fraction"].get<double>());
    std::printf(" %8.1f\n", r["wall_s"].get<double>());
  }
  // Observed order of the grid convergence of A/A0 (grids halving the spacing).
  for (std::size_t k = 2; k < rows.size(); ++k) {
    std::printf("  order over N = %zu..%zu:", rows[k - 2]["n"].get<std::size_t>(), rows[k]["n"].get<std::size_t>());
    for (std::size_t i = 0; i < rows[k]["curve"].size(); ++i) {
      const auto e = richardson_three(rows[k - 2]["curve"][i]["area_fraction"].get<double>(),
                                      rows[k - 1]["curve"][i]["area_fraction"].get<double>(),
                                      rows[k]["curve"][i]["area_fraction"].get<double>());
      if (e)
        std::printf("  %.2f (limit %.5f)", e->order, e->limit);
      else
        std::printf("  n/a");
    }
    std::printf("\n");
  }
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  if (!c.plot.empty()) bench::plot_kappa(rows, c.plot);
  return 0;
}

int run_spectral_vs_fem(const SpectralVsFemBenchCli& c) {
  const FemBenchSession session;
  const int rank = session.rank;
  const auto rows = bench::spectral_vs_fem(c.compare_h0, c.compare_refine, rank);
  if (rank != 0) return 0;
  std::printf("spectral layer against the FEM block, refine %d (100 x 100, 1 cm, H 0.7): A/A0 after the press at\n"
              "equal mean pressure; mu after the shear (top moved by uz / 2) at equal displacements\n",
              c.compare_refine);
  std::printf("  %9s %9s %9s %10s %12s %9s %9s %7s %9s %9s %9s %8s %8s\n", "h0 [m]", "rms slope", "FEM nodes", "uz [m]",
              "Fz [N]", "A/A0 FEM", "A/A0 spec", "diff", "mu FEM", "mu spec", "dmu/slope", "FEM s", "spec s");
  for (const auto& r : rows)
    std::printf("  %9.3g %9.3f %9zu %10.3g %12.4e %9.4f %9.4f %6.1f%% %9.5f %9.5f %8.2f%% %8.1f %8.2f%s\n",
                r["h0"].get<double>(), r["rms_slope"].get<double>(), r["fem_nodes"].get<std::size_t>(),
                r["uz"].get<double>(), r["fem_fz"].get<double>(), r["fem_area_fraction"].get<double>(),
                r["spectral_area_fraction"].get<double>(), 100 * r["area_difference"].get<double>(),
                r["fem_mu"].get<double>(), r["spectral_mu"].get<double>(),
                100 * r["mu_difference_per_slope"].get<double>(), r["fem_wall_s"].get<double>(),
                r["spectral_wall_s"].get<double>() + r["spectral_shear_wall_s"].get<double>(),
                r["fem_converged"].get<bool>() && r["spectral_converged"].get<bool>() &&
                        r["spectral_shear_converged"].get<bool>()
                    ? ""
                    : "  NOT CONVERGED");
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  if (!c.plot.empty()) bench::plot_spectral_vs_fem(rows, c.plot);
  return 0;
}

int run_accuracy(const AccuracyBenchCli& c) {
  const FemBenchSession session;
  const int rank = session.rank;
  const auto r = bench::accuracy(c.accuracy_h0, c.fem_refines, c.spectral_refines, rank);
  if (rank != 0) return 0;
  std::printf("speed against accuracy, one scene (100 x 100, 1 cm, h0 %.3g m, rms slope %.3f); reference: the finest FEM\n",
              r["h0"].get<double>(), r["rms_slope"].get<double>());
  std::printf("  %-9s %6s %9s %12s %10s %10s %10s\n", "model", "refine", "points", "p [Pa]", "A/A0", "error", "wall [s]");
  for (const auto& q : r["points"])
    std::printf("  %-9s %6d %9zu %12.4e %10.4f %9.2f%% %10.3g%s\n", q["model"].get<std::string>().c_str(),
                q["refine"].get<int>(), q["nodes"].get<std::size_t>(), q["pressure"].get<double>(),
                q["area_fraction"].get<double>(), 100 * q["error"].get<double>(), q["wall_s"].get<double>(),
                q["converged"].get<bool>() ? "" : "  NOT CONVERGED");
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  if (!c.plot.empty()) bench::plot_accuracy(r, c.plot);
  return 0;
}

int run_mesh_convergence(const MeshConvergenceBenchCli& c) {
  const FemBenchSession session;
  const int rank = session.rank;
  const LoadedSurface s = load_surface(c.mc_surface);
  if (!s.map.periodic) throw InputError(s.source, "not a periodic surface; the contact scene repeats the surface");
  if (c.mc_refines.empty() || !std::is_sorted(c.mc_refines.begin(), c.mc_refines.end()) || c.mc_refines.front() < 1)
    throw InputError("--refines", "give ascending refinements >= 1, e.g. 1 2 4 8");
  ContactScene o;  // the shear test; the bench sets the model (fem) and each refine
  o.uz = c.mc_uz;
  o.ux = c.mc_ux;
  o.normal_steps = c.mc_steps;
  o.shear_steps = c.mc_shear_steps;
  o.tolerance = c.mc_tol;
  o.poisson = c.mc_nu;
  o.refine = c.mc_refines.front();
  check_contact_scene(o);
  if (rank == 0)
    std::fprintf(stderr, "mesh convergence of the FEM shear test on %s (%zu x %zu, spacing %.3g m): uz %.3g m, ux %.3g m\n",
                 s.source.c_str(), s.map.nx, s.map.ny, s.map.dx, o.uz, o.ux);
  const auto r = bench::fem_mesh_convergence(s.map, o, c.mc_refines, rank);
  if (rank != 0) return 0;
  std::printf("FEM shear test over face refinements: %s, uz %.3g m in %d steps, ux %.3g m in %d, tol %.3g, nu %.3g\n",
              s.source.c_str(), o.uz, o.normal_steps, o.ux, o.shear_steps, o.tolerance, o.poisson);
  std::printf("  %6s %10s %9s %9s %10s %10s %9s %9s %9s\n", "refine", "spacing", "nodes", "A/A0 A", "peak mu", "at ux",
              "drift", "A/A0 B", "wall s");
  for (const auto& m : r["meshes"]) {
    if (m.contains("skipped")) {
      std::printf("  %6d %10.3g  skipped: %s\n", m["refine"].get<int>(), m["face_spacing"].get<double>(),
                  m["skipped"].get<std::string>().c_str());
      continue;
    }
    const auto num = [&](const char* k) { return m.contains(k) ? m[k].get<double>() : std::nan(""); };
    std::printf("  %6d %10.3g %9zu %9.4f %10.5f %10.3g %9.3g %9.4f %9.1f%s%s\n", m["refine"].get<int>(),
                m["face_spacing"].get<double>(), m["nodes"].get<std::size_t>(), num("pressed_area_fraction"), num("mu"),
                num("mu_ux"), num("mu_drift"), num("sheared_area_fraction"), m["wall_s"].get<double>(),
                m["converged"].get<bool>() ? "" : "  FAILED",
                m.value("friction_converged", true) ? "" : "  mu still creeping (drift > 5 %)");
  }
  for (const auto& e : r["extrapolations"]) {
    const auto& k = e["refines"];
    std::printf("  Richardson over refine %d, %d, %d:", k[0].get<int>(), k[1].get<int>(), k[2].get<int>());
    for (const char* q : {"mu", "pressed_area_fraction", "sheared_area_fraction"}) {
      if (!e.contains(q)) continue;
      if (e[q].contains("limit"))
        std::printf("  %s %.5g +- %.2g (order %.2f)", q, e[q]["limit"].get<double>(), e[q]["error"].get<double>(),
                    e[q]["order"].get<double>());
      else
        std::printf("  %s not in the asymptotic range (finest two %.2g apart)", q,
                    e[q]["finest_difference"].get<double>());
      if (e[q].contains("friction_converged") && !e[q]["friction_converged"].get<bool>())
        std::printf(" [uses a creeping mu]");
    }
    std::printf("\n");
  }
  if (r["extrapolations"].empty()) std::printf("  no three finished meshes with one refinement ratio: no extrapolation\n");
  if (!c.json.empty()) {
    Provenance prov;
    prov.command = "bench mesh-convergence";
    prov.inputs = {{"surface", c.mc_surface}};
    prov.parameters = contact_scene_json(o);
    prov.parameters["refines"] = c.mc_refines;
    prov.parameters["ranks"] = session_size();
    prov.model = "fem: graded trilinear cube, frictionless contact, Signorini iteration (thesis sec. 4.2)";
    double total = 0;
    for (const auto& m : r["meshes"]) total += m.value("wall_s", 0.0);
    prov.timings = {{"total", total}};
    nlohmann::json out = r;
    out["provenance"] = prov.to_json();
    write_text_atomically(c.json, out.dump(2) + "\n");
  }
  if (!c.plot.empty()) bench::plot_mesh_convergence(r, c.plot);
  return 0;
}

int run_hertz(const HertzBenchCli& c) {
  const FemBenchSession session;
  const int rank = session.rank;
  const auto rows = bench::hertz(c.hertz_meshes, c.hertz_radius, c.hertz_uz, c.hertz_layers, rank);
  if (rank != 0) return 0;
  std::printf("Hertz: paraboloid R = %g m pressed %g m into a 20 mm block (E = 1, nu = 0.45), %d layers per level\n",
              c.hertz_radius, c.hertz_uz, c.hertz_layers);
  // The fitted radius (pressure profile) is the measure; the node count steps with the lattice.
  std::printf("  %5s %10s %9s %12s %10s %10s %9s %9s %9s %9s %8s\n", "n", "h [m]", "nodes", "Fz [N]", "a_fit",
              "a_Hertz(F)", "err a", "err F(a)", "err p0", "count a", "wall s");
  double prev = 0;
  for (const auto& r : rows) {
    const double e = r["fit_radius_error"].get<double>();
    std::printf("  %5d %10.3g %9zu %12.5e %10.5g %10.5g %8.2f%% %8.2f%% %8.2f%% %8.2f%% %8.1f", r["n"].get<int>(),
                r["h"].get<double>(), r["nodes"].get<std::size_t>(), r["fz"].get<double>(), r["a_fit"].get<double>(),
                r["a_hertz"].get<double>(), 100 * e, 100 * r["force_error"].get<double>(),
                100 * r["fit_p0_error"].get<double>(), 100 * r["radius_error"].get<double>(), r["wall_s"].get<double>());
    if (prev != 0 && e != 0) std::printf("   order %.2f", std::log(std::abs(prev / e)) / std::log(2.0));
    std::printf("\n");
    prev = e;
  }
  // Self-convergence of Fz at the fixed indentation (meshes halving h): order and Richardson limit.
  for (std::size_t k = 2; k < rows.size(); ++k) {
    const double f2 = rows[k]["fz"].get<double>();
    const auto e = richardson_three(rows[k - 2]["fz"].get<double>(), rows[k - 1]["fz"].get<double>(), f2);
    if (!e) {
      std::printf("  Fz over n = %d..%d: not in the asymptotic range\n", rows[k - 2]["n"].get<int>(),
                  rows[k]["n"].get<int>());
      continue;
    }
    std::printf("  Fz over n = %d..%d: observed order %.2f, extrapolated %.5e N +- %.1e (finest off by %.2f%%)\n",
                rows[k - 2]["n"].get<int>(), rows[k]["n"].get<int>(), e->order, e->limit, e->error,
                100 * (f2 / e->limit - 1));
  }
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  return 0;
}

int run_spot(const SpotBenchCli& c) {
  // The spot must fit in the 64 x 64 obstacle with flat ground around it.
  for (int k : c.spot_sizes)
    if (k < 1 || k > 16) throw InputError("--sizes", "give spot sizes from 1 to 16 raised vertices per side");
  for (int r : c.spot_refines)
    if (r < 1) throw InputError("--refines", "give face refinements >= 1");
  if (c.spot_layers < 1) throw InputError("--layers", "give at least 1 brick layer per level");
  const FemBenchSession session;
  const int rank = session.rank;
  const auto rows = bench::contact_spot(c.spot_sizes, c.spot_refines, c.spot_layers, rank);
  if (rank != 0) return 0;
  std::printf("small contact spots: k x k raised vertices of a flat 64 x 64 obstacle (0.1 mm), touched 0.1 um deep by\n"
              "the FEM cube (%d layers per level) and the spectral layer on the same face lattice; local compliance =\n"
              "uz / Fz less the far field (block L / (E A), layer L / (M A)), in m/N for E = 1 Pa\n",
              c.spot_layers);
  std::printf("  %5s %6s %9s %11s %6s %11s %11s %6s %11s %8s %8s\n", "spot", "refine", "FEM nodes", "Fz FEM [N]",
              "nodes", "c FEM", "Fz spec [N]", "points", "c spec", "c ratio", "FEM s");
  for (const auto& r : rows)
    std::printf("  %2dx%-2d %6d %9zu %11.4e %6lld %11.4e %11.4e %6lld %11.4e %8.3f %8.1f\n", r["spot_vertices"].get<int>(),
                r["spot_vertices"].get<int>(), r["refine"].get<int>(), r["fem_nodes"].get<std::size_t>(),
                r["fem_fz"].get<double>(), r["fem_contact_nodes"].get<long long>(),
                r["fem_local_compliance"].get<double>(), r["spectral_fz"].get<double>(),
                r["spectral_contact_points"].get<long long>(), r["spectral_local_compliance"].get<double>(),
                r["local_compliance_ratio"].get<double>(), r["fem_wall_s"].get<double>());
  if (!c.json.empty()) write_text_atomically(c.json, rows.dump(2) + "\n");
  return 0;
}

}  // namespace

BenchEntry add_spectral_speed_bench(CLI::App& bench) {
  auto o = std::make_shared<SpectralSpeedBenchCli>();
  CLI::App* ss = bench.add_subcommand("spectral", "Speed of the spectral normal-contact solver (10 loads per N x N surface).");
  ss->add_option("--sizes", o->spectral_sizes, "grid sizes N")->check(CLI::Range(2, 65536))->capture_default_str();
  ss->add_option("--loads", o->spectral_loads, "loads per surface")->check(CLI::Range(1, 1000000))->capture_default_str();
  ss->add_option("--threads", o->threads, "FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
  ss->add_option("--tol", o->spectral_tol, "relative l1 pressure change that ends a solve (>= 1e-9: single-precision CG)")->capture_default_str();
  ss->add_option("--admit-every", o->admit_every, "iterations between admissions of penetrating points")
      ->capture_default_str();
  ss->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {ss, [o] { return run_spectral_speed(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_spectral_shear_bench(CLI::App& bench) {
  auto o = std::make_shared<SpectralShearBenchCli>();
  CLI::App* sh = bench.add_subcommand("spectral-shear", "Speed of the spectral shear test (Problem A then B) on an N x N surface.");
  sh->add_option("--size", o->shear_n, "grid size N")->check(CLI::Range(2, 65536))->capture_default_str();
  sh->add_option("--uz", o->shear_uz, "final approach of the far face, m (surface: h0 1e-5 m over 1 cm)")
      ->capture_default_str();
  sh->add_option("--ux", o->shear_ux, "final tangential displacement of the far face, m")->capture_default_str();
  sh->add_option("--steps", o->shear_steps, "steps of each phase")->check(CLI::Range(1, 1000000))->capture_default_str();
  sh->add_option("--threads", o->threads, "FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
  sh->add_option("--tol", o->spectral_tol, "relative l1 pressure change that ends a solve (>= 1e-9: single-precision CG)")
      ->capture_default_str();
  sh->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {sh, [o] { return run_spectral_shear(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_kappa_bench(CLI::App& bench) {
  auto o = std::make_shared<KappaBenchCli>();
  CLI::App* ka = bench.add_subcommand("kappa", "Low-pressure kappa and the grid convergence of A/A0, spectral half-space.");
  ka->add_option("--sizes", o->kappa_sizes, "grid sizes N sampling the same surface")->check(CLI::Range(2, 65536))->capture_default_str();
  ka->add_option("--band", o->kappa_band, "q1 = the Nyquist wavenumber of a band x band grid")->check(CLI::Range(1, 1000000))->capture_default_str();
  ka->add_option("--seeds", o->kappa_seeds, "surfaces averaged")->check(CLI::Range(1, 1000000))->capture_default_str();
  ka->add_flag("--period", o->period_effect, "the period effect instead: spacing kept, period growing with N");
  ka->add_option("--threads", o->threads, "FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
  ka->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  ka->add_option("--plot", o->plot, "draw A/A0 against sigma* per grid with Persson's and BGT's lines (SVG)")->type_name("OUTPUT");
  return {ka, [o] { return run_kappa(*o); }, &o->json, &o->plot, nullptr};
}

BenchEntry add_spectral_vs_fem_bench(CLI::App& bench) {
  auto o = std::make_shared<SpectralVsFemBenchCli>();
  CLI::App* vs = bench.add_subcommand("spectral-vs-fem", "A/A0 and mu of the spectral layer against the FEM block over slopes (MPI ok).");
  vs->add_option("--h0", o->compare_h0, "rms heights of the scenes, m")->capture_default_str();
  vs->add_option("--refine", o->compare_refine, "face refinement of both models")->capture_default_str();
  vs->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  vs->add_option("--plot", o->plot, "draw the difference against rms slope (SVG)")->type_name("OUTPUT");
  return {vs, [o] { return run_spectral_vs_fem(*o); }, &o->json, &o->plot, nullptr};
}

BenchEntry add_accuracy_bench(CLI::App& bench) {
  auto o = std::make_shared<AccuracyBenchCli>();
  CLI::App* ac = bench.add_subcommand("accuracy", "Speed against accuracy of every model on one scene (MPI ok; minutes).");
  ac->add_option("--h0", o->accuracy_h0, "rms height of the scene, m")->capture_default_str();
  ac->add_option("--fem-refines", o->fem_refines, "FEM face refinements (the last is the reference)")->check(CLI::Range(1, 1000000))->capture_default_str();
  ac->add_option("--spectral-refines", o->spectral_refines, "spectral grid refinements")->check(CLI::Range(1, 1000000))->capture_default_str();
  ac->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  ac->add_option("--plot", o->plot, "draw wall time against error (SVG)")->type_name("OUTPUT");
  return {ac, [o] { return run_accuracy(*o); }, &o->json, &o->plot, nullptr};
}

BenchEntry add_mesh_convergence_bench(CLI::App& bench) {
  auto o = std::make_shared<MeshConvergenceBenchCli>();
  CLI::App* mc = bench.add_subcommand(
      "mesh-convergence",
      "Peak mu and A/A0 of one FEM shear test over face refinements, with Richardson's limit (MPI ok; long).");
  mc->footer(
      "The shear test (Problem A, then B) on --surface at each --refines value (face spacing = surface spacing /\n"
      "refine). A mesh estimated above 90 % of physical memory (with the lean AMG hierarchy where the standard\n"
      "one would not fit) is skipped. Over each three successive finished meshes with one refinement ratio:\n"
      "the observed order, the extrapolated value and its GCI error band.\n"
      "Example: mpirun -np 2 wetroad bench mesh-convergence --surface d32.h5 --refines 1 2 4 8 --json mc.json");
  mc->add_option("--surface", o->mc_surface, "surface file (periodic HDF5 height map)")->type_name("FILE")->required();
  mc->add_option("--uz", o->mc_uz, "normal displacement of the top, m")->capture_default_str();
  mc->add_option("--ux", o->mc_ux, "tangential displacement of the top, m")->capture_default_str();
  mc->add_option("--steps", o->mc_steps, "normal steps")->check(CLI::Range(1, 1000000))->capture_default_str();
  mc->add_option("--shear-steps", o->mc_shear_steps, "shear steps")->capture_default_str();
  mc->add_option("--tol", o->mc_tol, "Signorini tolerance (relative change)")->capture_default_str();
  mc->add_option("--nu", o->mc_nu, "Poisson's ratio")->capture_default_str();
  mc->add_option("--refines", o->mc_refines, "face refinements, ascending")->check(CLI::Range(1, 1000000))->capture_default_str();
  mc->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  mc->add_option("--plot", o->plot, "draw peak mu against face spacing with the limit (SVG)")->type_name("OUTPUT");
  return {mc, [o] { return run_mesh_convergence(*o); }, &o->json, &o->plot, &o->mc_surface};
}

BenchEntry add_hertz_bench(CLI::App& bench) {
  auto o = std::make_shared<HertzBenchCli>();
  CLI::App* he = bench.add_subcommand("hertz", "Hertz validation of the FEM contact solver over three meshes (MPI ok).");
  he->add_option("--meshes", o->hertz_meshes, "elements per face side")->check(CLI::Range(1, 1000000))->capture_default_str();
  he->add_option("--radius", o->hertz_radius, "paraboloid radius of curvature, m")->capture_default_str();
  he->add_option("--uz", o->hertz_uz, "top displacement, m")->capture_default_str();
  he->add_option("--layers", o->hertz_layers, "brick layers per in-plane spacing (bulk grading)")->capture_default_str();
  he->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {he, [o] { return run_hertz(*o); }, &o->json, nullptr, nullptr};
}

BenchEntry add_spot_bench(CLI::App& bench) {
  auto o = std::make_shared<SpotBenchCli>();
  CLI::App* st = bench.add_subcommand("spot", "Compliance of one- to few-node contact spots, FEM bricks against spectral pixels (MPI ok).");
  st->footer(
      "Where the FEM's face error on rough surfaces comes from (docs/fem-solver.md): a spot of k x k raised obstacle\n"
      "vertices is touched by both models on the same face lattice; the ratio of their local compliances is 1 for\n"
      "a resolved spot and shows what a node of the bricks' face yields against a pixel of uniform pressure.\n"
      "Example: wetroad bench spot --sizes 1 2 4 --refines 1 2 4  (the defaults take about 2 min)");
  st->add_option("--sizes", o->spot_sizes, "spot sizes, raised obstacle vertices per side")->check(CLI::Range(1, 1000000))->capture_default_str();
  st->add_option("--refines", o->spot_refines, "face refinements")->check(CLI::Range(1, 1000000))->capture_default_str();
  st->add_option("--layers", o->spot_layers, "brick layers per in-plane spacing (bulk grading)")->capture_default_str();
  st->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {st, [o] { return run_spot(*o); }, &o->json, nullptr, nullptr};
}

}  // namespace wr::app
