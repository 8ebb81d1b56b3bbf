#pragma once
// The free clusters of a gap map: connected sets of cells with gap > 0 (4-connectivity, through
// shared faces, periodic), and whether each winds around the torus in x and in y.
//
// Winding: a breadth-first search from one cell of the cluster carries every cell's unwrapped
// position, i.e. the number of times (wx, wy) the path to it crossed the periodic seam. An edge
// to a cell already reached with another unwrap offset closes a cycle whose net displacement is
// the difference of the offsets times the period: a cycle that winds. Every cycle is a sum of the
// cycles the non-tree edges close, so a cluster winds in x iff one of those edges differs in x.
// Cost O(cells), memory 3 ints per cell.
#include <cstdint>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

struct FreeClusters {
  std::vector<std::int32_t> label;  // per cell: the cluster's index, -1 for a contact cell (gap <= 0)
  std::vector<bool> winds_x, winds_y;  // per cluster
  std::size_t free_cells = 0;
  bool any_x() const;
  bool any_y() const;
};

// `gap` already checked (finite, >= 0, periodic, non-empty).
FreeClusters label_free_clusters(const HeightMap& gap);

}  // namespace wr
