#include "water/drained_limit.hpp"

#include <algorithm>
#include <cmath>

#include "lib/core/errors.hpp"
#include "water/height_order.hpp"
#include "water/lifted_union_find.hpp"

namespace wr {

BigVector drained_limit_levels(const HeightMap& map, int connectivity, Boundary boundary) {
  const GridTopology t(map.nx, map.ny, map.dx, map.dy, connectivity, boundary);
  const std::size_t n = map.h.size();
  for (double v : map.h)
    if (!std::isfinite(v)) throw InputError("", "the surface has NaN/Inf heights; fill dropouts first");
  const std::vector<std::uint32_t> order = cells_in_height_order(map.h);
  BigVector level(n, std::nan(""));
  LiftedUnionFind uf(n);
  std::vector<char> active(n, 0), wrapped(n, 0);
  // Members of each not-yet-wrapped component as a linked list (head at the root), so that the
  // level can be assigned to all of them when the component first reaches infinity.
  constexpr std::uint32_t kEnd = 0xffffffffu;
  std::vector<std::uint32_t> next(n, kEnd), tail(n);
  for (std::size_t i = 0; i < n; ++i) tail[i] = static_cast<std::uint32_t>(i);
  auto drain_all = [&](std::uint32_t root, double z) {
    for (std::uint32_t c = root; c != kEnd; c = next[c]) level[c] = std::max(z, map.h[c]);
    wrapped[root] = 1;
  };
  for (const std::uint32_t c : order) {
    active[c] = 1;
    const double hc = map.h[c];
    bool outlet = false;
    visit_active_edges(
        t, c, active, uf, [&] { outlet = true; },
        [&](const LiftedUnionFind::Edge& e, const Neighbour& nb) {
          if (!wrapped[e.rc] && LiftedUnionFind::wraps(e, nb)) drain_all(e.rc, hc);
        },
        [&](const LiftedUnionFind::Edge& e, const Neighbour& nb) {
          const std::uint32_t rc = e.rc, rn = e.rn;
          const bool w = wrapped[rc] || wrapped[rn];
          if (w) {  // the other side spills into infinity at this level
            if (!wrapped[rc]) drain_all(rc, hc);
            if (!wrapped[rn]) drain_all(rn, hc);
          }
          const std::uint32_t big = uf.unite(e, nb), small = big == rc ? rn : rc;
          if (!w) {  // concatenate member lists
            next[tail[big]] = small;
            tail[big] = tail[small];
          }
          wrapped[big] = w;
        });
    std::int32_t cx, cy;
    const std::uint32_t r = uf.find(c, cx, cy);
    if (outlet && !wrapped[r]) drain_all(r, hc);
    if (wrapped[r] && std::isnan(level[c])) level[c] = hc;
  }
  return level;
}

}  // namespace wr
