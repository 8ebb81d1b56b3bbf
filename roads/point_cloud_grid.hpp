#pragma once
// Scattered x, y, z points (laser scanners, photogrammetry) onto a regular grid.
//
// Method: CGAL's 2-D Delaunay triangulation of the (x, y) positions; each grid node takes the
// linear interpolant of the triangle it falls in (barycentric weights of its three corners).
// Nodes outside the points' convex hull, or in a triangle with an edge longer than max_gap,
// are dropouts (NaN): a hole in the cloud stays a hole instead of being bridged by a long,
// flat triangle.
//
// Error of the linear interpolant (why max_gap matters): for f with |Hessian| <= M (spectral
// norm) the interpolant at x in a triangle with corners v_i and weights l_i is
//   |L f(x) - f(x)| <= (M / 2) sum_i l_i |v_i - x|^2 <= (M / 2) R^2 <= M D^2 / 6,
// R the radius of the triangle's smallest enclosing circle and D its longest edge (Jung's
// theorem: R <= D / sqrt 3). GriddedCloud::max_edge_used is the D of the worst triangle used.
//
// Grid: origin at the smallest x and y of the points; nx = floor((x_max - x_min) / dx) + 1
// nodes along x (likewise y), so no node lies beyond the points. Not periodic.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

struct CloudPoint {
  double x, y, z;  // m
};

struct PointCloudGridOptions {
  double dx = 0;                  // m, > 0
  std::optional<double> dy;       // m; default dx
  std::optional<double> max_gap;  // m; default kDefaultGapSpacings x the mean point spacing
};

// Default max_gap in mean point spacings sqrt(hull area / points): the longest Delaunay edge
// of uniformly random points stays near 4 spacings up to 1e6 points, so 5 bridges no genuine
// hole wider than 5 spacings and leaves ordinary sampling gaps alone.
inline constexpr double kDefaultGapSpacings = 5.0;

// Refused: a grid with more nodes than this per point (100 times finer than the cloud along
// each side): everything but the points would be interpolated.
inline constexpr double kMaxNodesPerPoint = 1e4;

struct GriddedCloud {
  HeightMap map;                 // NaN at dropouts; kind map, periodic false
  std::size_t points = 0;        // points read
  std::size_t duplicates = 0;    // points at an (x, y) already taken (the first one kept)
  std::size_t dropouts = 0;      // grid nodes outside the hull or in a triangle longer than max_gap
  double mean_spacing = 0;       // m, sqrt(hull area / distinct points)
  double max_gap = 0;            // m, the one applied
  double max_edge_used = 0;      // m, longest edge of the triangles that gave heights
  double x0 = 0, y0 = 0;         // m, position of grid node (0, 0)
  std::string method;            // one line for outputs and provenance
};

// Grids `points`. InputError(source, ...) for fewer than 3 points, non-finite coordinates,
// points all on one line in (x, y), a non-positive spacing or max_gap, a grid of more than
// kMaxNodesPerPoint nodes per point, or one that would not fit in memory.
GriddedCloud grid_point_cloud(const std::vector<CloudPoint>& points, const PointCloudGridOptions& opt,
                              const std::string& source);

// Reads "x y z" per line (whitespace, comma or semicolon separated; '#' comments; one header
// line of column names, and nothing else that is not a number, allowed before the first point;
// further columns ignored; a UTF-8 BOM skipped; LF, CRLF or CR line ends) and scales all three
// coordinates by unit_scale (m per unit). InputError naming the file, line and column otherwise.
std::vector<CloudPoint> read_point_cloud_text(const std::string& path, double unit_scale);

}  // namespace wr
