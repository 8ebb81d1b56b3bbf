#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "water/grid_topology.hpp"

namespace wr {

// Union-find over activated cells that also tracks each cell's tile offset in the periodic
// plane relative to its root.
struct LiftedUnionFind {
  std::vector<std::uint32_t> parent;
  std::vector<std::int32_t> ox, oy;
  std::vector<std::uint32_t> size;
  explicit LiftedUnionFind(std::size_t n) : parent(n), ox(n, 0), oy(n, 0), size(n, 1) {
    for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
  }
  // Root of x and the offset lift(x) - lift(root); compresses the path.
  std::uint32_t find(std::uint32_t x, std::int32_t& dx, std::int32_t& dy) {
    std::uint32_t r = x;
    std::int32_t sx = 0, sy = 0;
    while (parent[r] != r) {
      sx += ox[r];
      sy += oy[r];
      r = parent[r];
    }
    // Second pass: point every node of the path at the root with its total offset.
    std::int32_t rx = sx, ry = sy;
    while (parent[x] != x) {
      const std::uint32_t next = parent[x];
      const std::int32_t nxo = ox[x], nyo = oy[x];
      parent[x] = r;
      ox[x] = rx;
      oy[x] = ry;
      rx -= nxo;
      ry -= nyo;
      x = next;
    }
    dx = sx;
    dy = sy;
    return r;
  }

  // An edge from cell c to its neighbour nb (both in the structure): their roots, and whether
  // they are one component reached through a different periodic copy of nb (a wrap).
  struct Edge {
    std::uint32_t rc, rn;
    std::int32_t cx, cy, nx, ny;  // offsets of c and nb relative to their roots
  };
  Edge edge(std::uint32_t c, const Neighbour& nb) {
    Edge e;
    e.rc = find(c, e.cx, e.cy);
    e.rn = find(nb.cell, e.nx, e.ny);
    return e;
  }
  // Same component, different copy of the neighbour: the component wraps around the torus.
  static bool wraps(const Edge& e, const Neighbour& nb) {
    return e.rc == e.rn && (e.nx - e.cx != nb.sx || e.ny - e.cy != nb.sy);
  }
  // Unites the two components of an edge with distinct roots (smaller under larger, with the
  // offset that puts c's copy next to nb's); returns the new root.
  std::uint32_t unite(const Edge& e, const Neighbour& nb) {
    std::uint32_t big = e.rc, small = e.rn;
    std::int32_t offx = e.nx - nb.sx - e.cx, offy = e.ny - nb.sy - e.cy;  // lift(rc) - lift(rn)
    if (size[e.rc] < size[e.rn]) {
      std::swap(big, small);
    } else {
      offx = -offx;
      offy = -offy;
    }
    parent[small] = big;
    ox[small] = offx;
    oy[small] = offy;
    size[big] += size[small];
    return big;
  }
};


// The sweep step shared by the water algorithms: for cell c, just activated, visit the edges to
// its active neighbours. `outlet()` is called for a neighbour beyond a bounded map's edge,
// `same(edge, nb)` when both ends are already one component, `merge(edge, nb)` otherwise.
template <class Outlet, class Same, class Merge>
void visit_active_edges(const GridTopology& t, std::uint32_t c, const std::vector<char>& active,
                        LiftedUnionFind& uf, Outlet&& outlet, Same&& same, Merge&& merge) {
  for (int k = 0; k < t.connectivity(); ++k) {
    const Neighbour nb = t.neighbour(c % t.nx(), c / t.nx(), k);
    if (nb.outside) {
      outlet();
      continue;
    }
    if (!active[nb.cell] || nb.cell == c) continue;
    const LiftedUnionFind::Edge e = uf.edge(c, nb);
    if (e.rc == e.rn)
      same(e, nb);
    else
      merge(e, nb);
  }
}

}  // namespace wr
