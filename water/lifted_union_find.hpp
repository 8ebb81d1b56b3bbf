#pragma once
#include <cstdint>
#include <vector>

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
};


}  // namespace wr
