#include "water/depression_hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "lib/core/errors.hpp"
#include "water/height_order.hpp"
#include "water/lifted_union_find.hpp"

namespace wr {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr std::uint32_t kOutlet = 0xfffffffeu;

// Steepest-descent receiver of every cell; flats route breadth-first to their nearest
// draining cell; pits receive kNone; cells draining off a bounded map kOutlet.
std::vector<std::uint32_t> route_downhill(const GridTopology& t, const std::vector<double>& h) {
  const std::size_t n = t.cells(), nx = t.nx();
  std::vector<std::uint32_t> down(n, kNone);
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t ix = c % nx, iy = c / nx;
    double best = 0;
    for (int k = 0; k < t.connectivity(); ++k) {
      const Neighbour nb = t.neighbour(ix, iy, k);
      if (nb.outside) {  // the outlet lies infinitely low
        down[c] = kOutlet;
        break;
      }
      const double slope = (h[c] - h[nb.cell]) / nb.distance;
      if (slope > best) {
        best = slope;
        down[c] = nb.cell;
      }
    }
  }
  // Flats: breadth-first distance from draining cells over equal heights.
  std::vector<std::uint32_t> dist(n, kNone);
  std::deque<std::uint32_t> queue;
  for (std::size_t c = 0; c < n; ++c)
    if (down[c] != kNone) {
      dist[c] = 0;
      queue.push_back(static_cast<std::uint32_t>(c));
    }
  while (!queue.empty()) {
    const std::uint32_t c = queue.front();
    queue.pop_front();
    for (int k = 0; k < t.connectivity(); ++k) {
      const Neighbour nb = t.neighbour(c % nx, c / nx, k);
      if (nb.outside || dist[nb.cell] != kNone || h[nb.cell] != h[c]) continue;
      dist[nb.cell] = dist[c] + 1;
      queue.push_back(nb.cell);
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    if (down[c] != kNone || dist[c] == kNone) continue;
    for (int k = 0; k < t.connectivity(); ++k) {  // first neighbour (direction order) one step closer
      const Neighbour nb = t.neighbour(c % nx, c / nx, k);
      if (!nb.outside && h[nb.cell] == h[c] && dist[nb.cell] + 1 == dist[c]) {
        down[c] = nb.cell;
        break;
      }
    }
  }
  return down;
}

// The pit (or kOutlet) each cell's rain ends in.
std::vector<std::uint32_t> find_sinks(const std::vector<std::uint32_t>& down) {
  const std::size_t n = down.size();
  std::vector<std::uint32_t> sink(n, kNone), path;
  for (std::size_t c0 = 0; c0 < n; ++c0) {
    std::uint32_t c = static_cast<std::uint32_t>(c0);
    path.clear();
    while (sink[c] == kNone) {
      if (down[c] == kNone) {
        sink[c] = c;
        break;
      }
      if (down[c] == kOutlet) {
        sink[c] = kOutlet;
        break;
      }
      path.push_back(c);
      c = down[c];
    }
    for (std::uint32_t p : path) sink[p] = sink[c];
  }
  return sink;
}

}  // namespace

DepressionHierarchy::DepressionHierarchy(const HeightMap& map, int connectivity, Boundary boundary)
    : topo_(map.nx, map.ny, map.dx, map.dy, connectivity, boundary) {
  const std::size_t n = map.h.size();
  if (n >= kOutlet) throw InputError("", "maps beyond 4 billion cells are not supported by the water module");
  if (connectivity != 4 && connectivity != 8) throw InputError("--connectivity", "must be 4 or 8");
  h_.assign(map.h.begin(), map.h.end());
  for (double v : h_)
    if (!std::isfinite(v)) throw InputError("", "the surface has NaN/Inf heights; fill dropouts first");

  const std::vector<std::uint32_t> sink = find_sinks(route_downhill(topo_, h_));

  const std::vector<std::uint32_t> order = cells_in_height_order(h_);

  LiftedUnionFind uf(n);
  std::vector<char> active(n, 0), wrapped(n, 0);
  std::vector<int> top(n, -1);  // per union-find root: its top node
  owner_.assign(n, -1);
  const std::size_t nx = topo_.nx();

  auto new_node = [&](double level) {
    nodes_.emplace_back();
    nodes_.back().level = level;
    return static_cast<int>(nodes_.size() - 1);
  };
  auto mark_wrapped = [&](std::uint32_t root, double level) {
    if (wrapped[root]) return;
    wrapped[root] = 1;
    if (top[root] >= 0) nodes_[top[root]].wrap = std::min(nodes_[top[root]].wrap, level);
  };
  // Node receiving overflow that enters component `root` through saddle cell c: the rain node
  // of c's lowest active neighbour in that component (-1 when it drains off the map).
  auto entry_into = [&](std::uint32_t c, std::uint32_t root) {
    std::uint32_t best = kNone;
    for (int k = 0; k < topo_.connectivity(); ++k) {
      const Neighbour nb = topo_.neighbour(c % nx, c / nx, k);
      if (nb.outside || !active[nb.cell]) continue;
      std::int32_t dx, dy;
      if (uf.find(nb.cell, dx, dy) != root) continue;
      if (best == kNone || h_[nb.cell] < h_[best]) best = nb.cell;
    }
    const std::uint32_t s = sink[best];
    if (s == kOutlet) return -1;
    // A pit on a flat at exactly the saddle height may not be activated yet: its component's top.
    return owner_[s] >= 0 ? owner_[s] : top[root];
  };

  for (const std::uint32_t c : order) {
    active[c] = 1;
    const double hc = h_[c];
    bool outlet = false;
    visit_active_edges(
        topo_, c, active, uf, [&] { outlet = true; },
        [&](const LiftedUnionFind::Edge& e, const Neighbour& nb) {
          // The same component reached again: through a different copy of the neighbour?
          if (!wrapped[e.rc] && LiftedUnionFind::wraps(e, nb)) mark_wrapped(e.rc, hc);
        },
        [&](const LiftedUnionFind::Edge& e, const Neighbour& nb) {
          const std::uint32_t rc = e.rc, rn = e.rn;
          if (top[rc] < 0) {  // c alone so far: it simply joins the neighbour's component
            const std::uint32_t root = uf.unite(e, nb);
            top[root] = top[rn];
            wrapped[root] = wrapped[rn];
            return;
          }
          // Two depressions meet at saddle c: a merge node.
          const int a = top[rc], b = top[rn];
          const int p = new_node(hc);
          nodes_[p].child[0] = a;
          nodes_[p].child[1] = b;
          nodes_[p].entry[0] = entry_into(c, rn);  // overflow of a enters b's side
          nodes_[p].entry[1] = entry_into(c, rc);  // overflow of b enters a's side
          nodes_[p].ocean_at_birth = wrapped[rc] || wrapped[rn];
          nodes_[a].parent = p;
          nodes_[b].parent = p;
          const std::uint32_t big = uf.unite(e, nb);
          wrapped[big] = wrapped[rc] || wrapped[rn];
          top[big] = p;
        });
    std::int32_t cx, cy;
    const std::uint32_t rc = uf.find(c, cx, cy);
    if (top[rc] < 0) top[rc] = new_node(hc);  // a pit: new leaf
    if (outlet) mark_wrapped(rc, hc);
    owner_[c] = top[rc];
  }

  // Own cells of every node, in activation order (so sorted by height), and prefix sums.
  for (const std::uint32_t c : order) nodes_[owner_[c]].own_count += 1;
  std::uint32_t pos = 0;
  for (auto& nd : nodes_) {
    nd.own_begin = pos;
    pos += nd.own_count;
  }
  own_h.resize(n);
  own_prefix.resize(n);
  std::vector<std::uint32_t> fill(nodes_.size(), 0);
  for (const std::uint32_t c : order) {
    const DepressionNode& nd = nodes_[owner_[c]];
    own_h[nd.own_begin + fill[owner_[c]]++] = h_[c];
  }
  for (auto& nd : nodes_) {
    double s = 0;
    for (std::uint32_t i = 0; i < nd.own_count; ++i) own_prefix[nd.own_begin + i] = (s += own_h[nd.own_begin + i]);
  }
  for (auto& nd : nodes_) {  // children precede parents
    if (!nd.is_leaf())
      for (int k = 0; k < 2; ++k) {
        nd.child_cells += nodes_[nd.child[k]].sub_cells;
        nd.child_sum_h += nodes_[nd.child[k]].sub_sum_h;
      }
    nd.sub_cells = nd.child_cells + nd.own_count;
    nd.sub_sum_h = nd.child_sum_h + (nd.own_count ? own_prefix[nd.own_begin + nd.own_count - 1] : 0.0);
  }
  rain_node_.resize(n);
  for (std::size_t c = 0; c < n; ++c) rain_node_[c] = sink[c] == kOutlet ? -1 : owner_[sink[c]];
}

double DepressionHierarchy::volume(int node, double z) const {
  const DepressionNode& nd = nodes_[node];
  const auto first = own_h.begin() + nd.own_begin;
  const std::size_t k = std::upper_bound(first, first + nd.own_count, z) - first;
  const double prefix = k ? own_prefix[nd.own_begin + k - 1] : 0.0;
  return (nd.child_cells + double(k)) * z - (nd.child_sum_h + prefix);
}

double DepressionHierarchy::level_for_volume(int node, double v) const {
  const DepressionNode& nd = nodes_[node];
  // Largest k (cells of the own list under water) with V evaluated at own_h[k-1] <= v.
  std::size_t lo = 1, hi = nd.own_count;  // V at own_h[0] = V(level) <= v by contract
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    const double z = own_h[nd.own_begin + mid - 1];
    const double vz = (nd.child_cells + double(mid)) * z - (nd.child_sum_h + own_prefix[nd.own_begin + mid - 1]);
    if (vz <= v)
      lo = mid;
    else
      hi = mid - 1;
  }
  const std::size_t k = nd.own_count ? lo : 0;
  const double prefix = k ? own_prefix[nd.own_begin + k - 1] : 0.0;
  return (v + nd.child_sum_h + prefix) / (nd.child_cells + double(k));
}

}  // namespace wr
