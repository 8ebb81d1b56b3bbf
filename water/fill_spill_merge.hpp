#pragma once
// Fill-spill-merge: where a uniform rain of depth d stands on a surface, given its depression
// hierarchy (water/depression_hierarchy.hpp).
//
// Rain on each cell runs to the depression its routing leads to. Each depression holds water
// up to its spill level with a flat surface; excess spills over the saddle into the
// neighbouring depression, entering it where the saddle's lowest neighbour on that side
// drains; when both sides of a saddle are full they form one lake that rises above it.
// Modes:
//  - drained: a lake that reaches its own periodic image (torus) or the border (bounded map)
//    connects to infinity: water above that level leaves (drained_volume);
//  - stagnant: periodic and closed, nothing leaves; lakes rise past the drained limit up to a
//    flooded surface, and the stored volume equals the rain exactly.
// The equilibrium does not depend on the order in which the rain is poured.
#include <string>
#include <vector>

#include "lib/core/big_buffer.hpp"
#include "water/depression_hierarchy.hpp"

namespace wr {

enum class WaterMode { drained, stagnant };

struct WaterState {
  BigVector level;          // m, water surface per cell: max(h, lake level)
  double rain_depth = 0;    // m of water per projected area
  double coverage = 0;      // fraction of cells with level > h
  double stored_volume = 0; // m^3 per m^2 of projected area (a depth)
  double drained_volume = 0;// m^3 per m^2, left through infinity
  std::size_t lakes = 0;    // connected lakes (distinct lake nodes with wet cells)
  double mean_depth = 0;    // m, over wet cells
  double max_depth = 0;     // m
};

// rain_depth >= 0 (m). Throws InputError for a negative or non-finite depth.
WaterState fill_spill_merge(const DepressionHierarchy& dh, double rain_depth, WaterMode mode);

// Statistics of a water surface over ground heights: coverage, stored volume, depths, and the
// number of lakes (connected wet regions under the topology's connectivity).
void summarize_water(const GridTopology& topo, const std::vector<double>& ground, WaterState& w);

}  // namespace wr
