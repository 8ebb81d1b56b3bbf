#pragma once
// The drained limit computed directly: every cell's water level is the lowest level at which
// it connects to infinity, i.e. min over paths to infinity of the highest ground on the path
// (the minimax spill level). On a torus "infinity" is reached when a component of
// {h <= level} contains two different periodic copies of one cell; on a bounded map when it
// touches the border. One sweep over the cells in height order with a union-find that tracks
// periodic lifts. Independent of the depression hierarchy, it also checks fill-spill-merge at
// large rain.
#include <vector>

#include "lib/core/big_buffer.hpp"
#include "lib/core/height_map.hpp"
#include "water/grid_topology.hpp"

namespace wr {

// Water surface max(h, spill level) per cell. Throws InputError on NaN heights.
BigVector drained_limit_levels(const HeightMap& map, int connectivity, Boundary boundary);

}  // namespace wr
