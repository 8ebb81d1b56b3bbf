#pragma once
// The bricks of a graded block mesh that touch the nodes a rank owns, each with the independent
// nodes behind its 8 corners and the hanging-node interpolation weights: what the assembled
// stiffness (elastic_block_assembly.cpp) and the matrix-free one (matrix_free_stiffness.hpp)
// both sum over, so that the two are the same operator by construction of their brick sets.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "lib/fem/graded_mesh.hpp"

namespace wr {

// Calls f(layer, ids, weights) for every brick that touches a node in [own_begin, own_end):
// ids = the distinct independent nodes behind the 8 corners, weights = 8 x ids.size()
// (row-major: corner c's weight on ids[p] at c * ids.size() + p).
template <class F>
void for_each_local_brick(const GradedMesh& g, int rank, std::int32_t own_begin, std::int32_t own_end, F&& f) {
  std::vector<GradedMesh::Parent> ps;
  std::vector<std::int32_t> ids;
  std::vector<double> w;
  for (int e = 0; e < g.layers(); ++e) {
    const int l = g.layer_level(e);
    // Hanging parents lie at most one cell beyond a brick: two cells of margin suffice.
    const int i0 = std::max(0, g.owned_i_begin(rank, l) - 2);
    const int i1 = std::min(g.cells_x(l), g.owned_i_end(rank, l) + 2);
    for (int j = 0; j < g.cells_y(l); ++j)
      for (int i = i0; i < i1; ++i) {
        ids.clear();
        bool mine = false;
        int start[9];
        ps.clear();
        for (int c = 0; c < 8; ++c) {
          int p, pi, pj;
          g.corner(e, i, j, c, p, pi, pj);
          start[c] = int(ps.size());
          g.parents(p, pi, pj, ps);
        }
        start[8] = int(ps.size());
        for (const auto& q : ps) {
          if (std::find(ids.begin(), ids.end(), q.id) == ids.end()) ids.push_back(q.id);
          mine |= q.id >= own_begin && q.id < own_end;
        }
        if (!mine) continue;
        w.assign(8 * ids.size(), 0.0);
        for (int c = 0; c < 8; ++c)
          for (int k = start[c]; k < start[c + 1]; ++k)
            w[c * ids.size() + std::size_t(std::find(ids.begin(), ids.end(), ps[k].id) - ids.begin())] += ps[k].weight;
        f(e, ids, w);
      }
  }
}

}  // namespace wr
