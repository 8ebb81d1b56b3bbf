// `wetroad bench obstacle-rays`: the CLI of bench/bench_obstacle_rays.hpp.
#include <cstdio>
#include <memory>

#include "app/bench_cli.hpp"
#include "bench/bench_obstacle_rays.hpp"
#include "lib/io/atomic_output.hpp"

namespace wr::app {
namespace {

struct ObstacleRaysCli {
  std::size_t n = 300, rays = 200000;
  double tilt = 40;
  unsigned seed = 1;
  std::string json;
};

int run_obstacle_rays(const ObstacleRaysCli& c) {
  const nlohmann::json r = bench::obstacle_rays(c.n, c.rays, c.tilt, c.seed);
  std::printf("ray casting on a %zu x %zu default-scene obstacle, %zu rays within %.0f deg of the vertical\n", c.n, c.n,
              c.rays, c.tilt);
  std::printf("  %-22s %10s %10s %14s\n", "method", "build s", "query s", "rays/s");
  for (const char* m : {"walk", "aabb_tree"})
    std::printf("  %-22s %10.4f %10.4f %14.4g\n", m == std::string("walk") ? "lattice walk" : "CGAL AABB tree",
                r[m]["build_s"].get<double>(), r[m]["query_s"].get<double>(), r[m]["rays_per_s"].get<double>());
  std::printf("  hits by both %zu, by one only %zu, largest distance difference %.3g m (relief %.3g m)\n",
              r["hits_both"].get<std::size_t>(), r["hit_by_one_only"].get<std::size_t>(),
              r["max_t_difference_m"].get<double>(), r["relief_m"].get<double>());
  if (!c.json.empty()) write_text_atomically(c.json, r.dump(2) + "\n");
  return 0;
}

}  // namespace

BenchEntry add_obstacle_rays_bench(CLI::App& bench) {
  auto o = std::make_shared<ObstacleRaysCli>();
  CLI::App* s = bench.add_subcommand("obstacle-rays", "FEM ray casting: the lattice walk against CGAL's AABB tree.");
  s->footer(
      "The FEM measures each face node's gap along a ray to the triangulated obstacle (lib/contact/\n"
      "periodic_obstacle.hpp). This casts the same rays with the lattice walk in use and with CGAL's AABB tree\n"
      "over the same triangles (plus the periodic ring a ray can reach), and compares times and hits.\n"
      "Example: wetroad bench obstacle-rays --size 300 --rays 200000");
  s->add_option("--size", o->n, "lattice points per side")->check(CLI::Range(2, 65536))->capture_default_str();
  s->add_option("--rays", o->rays, "rays cast by each method")->check(CLI::Range(1, 1000000))->capture_default_str();
  s->add_option("--tilt", o->tilt, "largest angle of a ray from the vertical, degrees")->capture_default_str();
  s->add_option("--seed", o->seed, "surface and ray seed")->capture_default_str();
  s->add_option("--json", o->json, "write the results as JSON")->type_name("OUTPUT");
  return {s, [o] { return run_obstacle_rays(*o); }, &o->json, nullptr, nullptr};
}

}  // namespace wr::app
