#pragma once
// `wetroad fill`: the water of one request on one surface, in any mode, with the method checks.
//
// Requests: a rain depth, a target coverage (bisection on the rain depth, reusing the
// depression hierarchy), or the drained limit. Methods:
//  - torus (default): exact periodic drainage (water leaves only through a lake that reaches
//    its own periodic image);
//  - 3x3: the thesis's method: the surface tiled 3x3, the outer border an outlet, the central
//    tile kept. Exact only while every lake is shorter than the tile; the cells that differ
//    from the torus answer are counted and reported (the method's failure, detected).
// The thesis's literal rule (`cap`: level = min(spill level, h + dmax)) is kept for comparison
// only; its water is not flat and its coverage is the drained limit for every dmax > 0.
#include <optional>
#include <string>

#include "lib/core/height_map.hpp"
#include "water/fill_spill_merge.hpp"

namespace wr {

enum class Tiling { torus, three_by_three };
enum class FillRule { fill_spill_merge, cap };

struct FillRequest {
  std::optional<double> rain;      // m
  std::optional<double> coverage;  // target fraction in (0, 1]
  bool limit = false;              // the drained limit (every depression at its spill level)
  WaterMode mode = WaterMode::drained;
  Tiling tiling = Tiling::torus;
  FillRule rule = FillRule::fill_spill_merge;
  double dmax = 0;                 // m, rule cap
  int connectivity = 4;
  double coverage_tolerance = 0;   // 0: one cell
};

struct FillResult {
  WaterState water;                  // level, statistics
  std::string method;                // what computed it
  // Coverage target: the bracket found and, when the target lies in a jump of coverage(d),
  // the jump.
  std::optional<double> target;
  bool target_in_jump = false;
  double jump_low = 0, jump_high = 0;  // coverage just below / above the jump
  // 3x3 tiling check against the exact torus answer.
  std::optional<std::size_t> tiling_differing_cells;
  double tiling_max_difference = 0;    // m
  std::vector<std::string> warnings;
  double hierarchy_s = 0, fill_s = 0;  // timings
  std::size_t hierarchy_nodes = 0;
};

// `map` must be periodic for torus tiling and hold no NaN. Throws InputError for bad requests
// (negative or NaN rain, a coverage the mode cannot reach, non-periodic surface on a torus...).
FillResult fill_water(const HeightMap& map, const FillRequest& req);

// The 3N x 3N non-periodic tiling of a periodic map, and the central tile of such a field.
HeightMap tile_3x3(const HeightMap& map);
BigVector central_tile(const BigVector& field, std::size_t nx, std::size_t ny);

}  // namespace wr
