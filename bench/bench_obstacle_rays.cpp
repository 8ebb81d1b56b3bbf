// `wetroad bench obstacle-rays`: the FEM's ray casting against the triangulated obstacle, the
// lattice walk of PeriodicObstacle (Amanatides-Woo through the cells, two triangles per cell)
// against CGAL's AABB tree over the same triangles (lib/contact/periodic_obstacle.hpp).
#include "bench/bench_obstacle_rays.hpp"

#include <algorithm>
#include <cmath>
#include <list>
#include <numbers>
#include <random>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "bench/bench_common.hpp"
#include "lib/contact/periodic_obstacle.hpp"
#include "roads/synthesize.hpp"

namespace wr::bench {
namespace {

// Double coordinates, as the lattice walk uses: the two answer the same question in the same
// arithmetic, so their hits can be compared to rounding.
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// The tile's triangles and a ring of `margin` cells of its periodic images around it (a ray
// that starts inside the tile never leaves the ring within its reach).
std::vector<Triangle> lattice_triangles(const HeightMap& m, long margin) {
  auto z = [&](long i, long j) {
    const long nx = long(m.nx), ny = long(m.ny);
    return m.h[std::size_t(((j % ny) + ny) % ny) * m.nx + std::size_t(((i % nx) + nx) % nx)];
  };
  auto p = [&](long i, long j) { return Kernel::Point_3(double(i) * m.dx, double(j) * m.dy, z(i, j)); };
  std::vector<Triangle> t;
  t.reserve(std::size_t(2 * (long(m.nx) + 2 * margin) * (long(m.ny) + 2 * margin)));
  for (long j = -margin; j < long(m.ny) + margin; ++j)
    for (long i = -margin; i < long(m.nx) + margin; ++i) {
      // The lattice walk's split: along the diagonal (i, j) - (i+1, j+1).
      t.emplace_back(p(i, j), p(i + 1, j), p(i + 1, j + 1));
      t.emplace_back(p(i, j), p(i + 1, j + 1), p(i, j + 1));
    }
  return t;
}

}  // namespace

nlohmann::json obstacle_rays(std::size_t n, std::size_t rays, double max_tilt_deg, unsigned seed) {
  SynthParams sp;  // the default asphalt-like scene's spectrum on an n x n lattice
  sp.nx = sp.ny = n;
  sp.seed = seed;
  const HeightMap map = synthesize(sp).map;
  const auto [lo, hi] = std::minmax_element(map.h.begin(), map.h.end());
  const double relief = *hi - *lo, tilt = max_tilt_deg * std::numbers::pi / 180;
  const double reach = 2 * relief / std::cos(tilt);  // from above the highest point to below the lowest
  const long margin = long(std::ceil(reach * std::sin(tilt) / std::min(map.dx, map.dy))) + 1;

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0, map.lx()), uy(0, map.ly()), ua(0, 2 * std::numbers::pi), ut(0, tilt);
  std::vector<Vec3> from(rays), dir(rays);
  for (std::size_t k = 0; k < rays; ++k) {
    const double a = ua(rng), b = ut(rng);
    from[k] = Vec3{ux(rng), uy(rng), *hi + 0.1 * relief};
    dir[k] = Vec3{std::sin(b) * std::cos(a), std::sin(b) * std::sin(a), -std::cos(b)};
  }

  double t0 = now();
  const PeriodicObstacle walk(map);
  const double walk_build = now() - t0;
  std::vector<double> t_walk(rays, NAN), t_tree(rays, NAN);
  t0 = now();
  for (std::size_t k = 0; k < rays; ++k)
    if (const auto h = walk.cast(from[k], dir[k], reach)) t_walk[k] = h->t;
  const double walk_query = now() - t0;

  t0 = now();
  const std::vector<Triangle> tris = lattice_triangles(map, margin);
  Tree tree(tris.begin(), tris.end());
  tree.accelerate_distance_queries();  // builds the tree now, not inside the first query
  tree.build();
  const double tree_build = now() - t0;
  t0 = now();
  for (std::size_t k = 0; k < rays; ++k) {
    const Kernel::Point_3 p(from[k].x, from[k].y, from[k].z);
    const Kernel::Ray_3 ray(p, Kernel::Vector_3(dir[k].x, dir[k].y, dir[k].z));
    const auto hit = tree.first_intersection(ray);
    if (!hit) continue;
    if (const Kernel::Point_3* q = boost::get<Kernel::Point_3>(&hit->first))
      t_tree[k] = std::sqrt(CGAL::to_double(CGAL::squared_distance(p, *q)));
  }
  const double tree_query = now() - t0;

  std::size_t both = 0, differ = 0;
  double max_dt = 0;
  for (std::size_t k = 0; k < rays; ++k) {
    if (std::isnan(t_walk[k]) || std::isnan(t_tree[k])) {
      differ += std::isnan(t_walk[k]) != std::isnan(t_tree[k]);
      continue;
    }
    ++both;
    max_dt = std::max(max_dt, std::abs(t_walk[k] - t_tree[k]));
  }
  return {{"n", n},
          {"rays", rays},
          {"max_tilt_deg", max_tilt_deg},
          {"triangles_walk", 2 * n * n},
          {"triangles_tree", tris.size()},
          {"hits_both", both},
          {"hit_by_one_only", differ},
          {"max_t_difference_m", max_dt},
          {"relief_m", relief},
          {"walk", {{"build_s", walk_build}, {"query_s", walk_query}, {"rays_per_s", double(rays) / walk_query}}},
          {"aabb_tree", {{"build_s", tree_build}, {"query_s", tree_query}, {"rays_per_s", double(rays) / tree_query}}}};
}

}  // namespace wr::bench
