#pragma once
// The depression hierarchy of a surface: built once, reused for every rain depth.
//
// Construction (a Kruskal-type sweep, cf. Barnes, Callaghan & Wickert 2020): cells are
// activated in increasing height (ties by index); an activated cell joins the components of its
// active neighbours. A cell with no active neighbour starts a leaf depression (a pit); a cell
// that joins k >= 2 components is a saddle and creates k-1 binary merge nodes at its height.
// Each node owns the cells that joined its component while it was the top node, so its volume
// below a level z (m^3 per cell area) is V(z) = sum over its subtree cells with h <= z of (z-h),
// piecewise linear in z and inverted exactly.
//
// Periodicity is handled exactly on the torus: the union-find stores, for every cell, the tile
// offset of its copy in the infinite periodic plane relative to its component's root. When an
// edge joins two copies of the same cell that lie in different tiles, the component has
// reached its own periodic image: from that level on it connects to infinity (the drained
// "ocean"). On a bounded map (the thesis's 3x3 tiling) reaching the border plays that role.
//
// Rain routing (fixed rule, independent of processing order): every cell sends its rain to
// its steepest-descent neighbour (largest drop per distance, ties by direction order); cells
// of a flat without a lower neighbour route to the nearest flat cell that has one (breadth-
// first distance, ties by direction order); cells that drain nowhere are pits. Each node
// records where the overflow of each child enters the other child's subtree (the leaf that
// the saddle's lowest neighbour on that side drains to).
#include <cstdint>
#include <limits>
#include <vector>

#include "lib/core/height_map.hpp"
#include "water/grid_topology.hpp"

namespace wr {

struct DepressionNode {
  double level = 0;    // m: creation level (pit height for a leaf, saddle height for a merge)
  double wrap = std::numeric_limits<double>::infinity();  // m: level at which the component
                                                          // first reaches infinity (its own image / the outlet)
  bool ocean_at_birth = false;  // a child already reached infinity
  int parent = -1;
  int child[2] = {-1, -1};
  int entry[2] = {-1, -1};      // entry[k]: node where overflow of child[k] enters child[1-k]'s subtree
  std::uint32_t own_begin = 0;  // range of this node's own cells in DepressionHierarchy::own_h
  std::uint32_t own_count = 0;
  double sub_cells = 0;         // cells in the subtree (children + own)
  double sub_sum_h = 0;         // sum of their heights, m
  double child_cells = 0;       // cells in the children's subtrees
  double child_sum_h = 0;
  bool is_leaf() const { return child[0] < 0; }
  bool wraps() const { return wrap < std::numeric_limits<double>::infinity(); }
};

class DepressionHierarchy {
 public:
  // Throws InputError on NaN heights (fill dropouts first) and on maps beyond 2^32 cells.
  DepressionHierarchy(const HeightMap& map, int connectivity, Boundary boundary);

  const GridTopology& topology() const { return topo_; }
  const std::vector<DepressionNode>& nodes() const { return nodes_; }
  std::size_t cells() const { return topo_.cells(); }
  double height(std::uint32_t c) const { return h_[c]; }

  // Node that owns cell c; the node that receives the rain of cell c (-1: it leaves the map).
  int owner(std::uint32_t c) const { return owner_[c]; }
  int rain_node(std::uint32_t c) const { return rain_node_[c]; }

  // V_N(z), m (volume per unit cell area), for z >= level of N.
  double volume(int node, double z) const;
  // The level z >= level of N with V_N(z) = v (v >= V_N(level)).
  double level_for_volume(int node, double v) const;

  // Sorted own heights of all nodes, node by node, and their prefix sums.
  std::vector<double> own_h, own_prefix;

 private:
  GridTopology topo_;
  std::vector<double> h_;
  std::vector<int> owner_;
  std::vector<int> rain_node_;
  std::vector<DepressionNode> nodes_;
};

}  // namespace wr
