#pragma once
// Loading a surface for analysis: HDF5 (/height or /profile, design.md), X3P (ISO 25178-72,
// roads/x3p_file.hpp), a plain-text grid, or a text x y z point cloud gridded on CGAL's Delaunay
// triangulation (roads/point_cloud_grid.hpp). The format is found from the content (HDF5 and
// zip signatures), then the options: `points` reads text as a point cloud, otherwise as a grid.
//
// After reading, non-finite samples (NaN, Inf) are dropouts. They are counted and filled:
//  - maps: layer by layer from the edge of each hole inward, every dropout with at least one
//    valid 4-neighbour taking the mean of those neighbours (all cells of a layer are updated
//    from the previous layer, so the result does not depend on scan order); neighbours wrap
//    around when the map is periodic;
//  - profiles: linear interpolation between the nearest valid samples, constant beyond the ends.
// The mean plane (least squares a + bx x + by y over the valid samples) is then removed and
// its slopes reported; a periodic surface has only its mean level removed (a tilt would break
// the periodicity, so the fitted "tilt" of one period is texture, not trend). The dropout mask is kept so MPD can apply ISO 13473-1's own rules.
//
// Warnings (LoadedSurface::warnings): more than 10 % dropouts; heights beyond 0.1 m.
// Errors (InputError naming the file): missing or unreadable file, heights beyond 1 km (metres
// read from a file in another unit), not HDF5 (and not a text grid), no
// /height or /profile, wrong rank, missing or non-positive dx, a 1x1 map or a profile under
// 8 samples, every sample a dropout, a size that does not fit in memory.
#include <optional>
#include <string>
#include <vector>

#include "lib/core/height_map.hpp"
#include "roads/surface_file.hpp"

namespace wr {

// For inputs that do not carry their own grid: text grids and point clouds.
struct TextGridOptions {
  std::optional<double> dx;  // m; required for text grids and point clouds (the grid to make)
  std::optional<double> dy;  // m; default dx
  double unit_scale = 1.0;   // metres per unit of the file (heights; all of x, y, z for points)
  bool periodic = false;     // measured data is not periodic unless said so (text grids)
  bool points = false;       // the text holds x y z points, not a grid
  std::optional<double> max_gap;  // m, point clouds: longest triangle edge interpolated across
  // The text-only options the user gave (e.g. "--unit"): refused for HDF5 and X3P files, which
  // carry their own spacing, units and periodicity, rather than silently ignored.
  std::vector<std::string> given;
};

struct LoadedSurface {
  HeightMap map;                       // dropouts filled, mean plane removed
  std::vector<unsigned char> dropout;  // 1 where the input had no valid sample
  std::size_t dropouts = 0;
  double tilt_x = 0, tilt_y = 0;       // removed mean-plane slopes, m/m
  double offset = 0;                   // mean level (removed unless Levels::keep), m
  double kept_offset = 0;              // the part of `offset` still in the map (Levels::keep), m
  double unit_scale = 1.0;             // metres per height unit of the file (heights are in m now)
  std::string source;                  // file path
  std::string format;                  // "hdf5", "x3p", "text" or "points"
  std::string detail;                  // format-specific facts for describe_import (one line)
  std::optional<SynthesisRecord> synthesis;
  // What the caller should tell the user (one line each): a map mostly of dropouts, heights
  // beyond any road texture (a unit left out).
  std::vector<std::string> warnings;
};

// The water module and the contact scene need a 2-D map that repeats: InputError naming the
// file when `s` is a 1-D profile or not periodic (`why` says what needs it).
void require_periodic_map(const LoadedSurface& s, const std::string& why);

// What the loader does with the mean level of a periodic map: remove it (analysis and contact
// work about the mean plane), or keep the file's own levels (the water module writes the wet
// surface at the input's levels, so that nothing is removed, restored and removed again). A
// map that is not periodic always loses its mean plane (tilt included).
enum class Levels { remove_mean, keep };

LoadedSurface load_surface(const std::string& path, const TextGridOptions& text = {},
                           Levels levels = Levels::remove_mean);

// One line saying what was read: format, grid, spacing, unit, invalid points and what filled
// them, and the format's own facts (X3P data type, checksums; point-cloud method).
std::string describe_import(const LoadedSurface& s);

// Fills dropouts of `map` in place by the rule above; returns how many were filled.
std::size_t fill_dropouts(HeightMap& map);

// Removes the least-squares mean plane over samples with dropout[i] == 0; returns
// {offset, tilt_x, tilt_y}.
struct MeanPlane {
  double offset, tilt_x, tilt_y;
};
MeanPlane remove_mean_plane(HeightMap& map, const std::vector<unsigned char>& dropout);
// The same plane, fitted but not removed.
MeanPlane fit_mean_plane(const HeightMap& map, const std::vector<unsigned char>& dropout);

// Metres per unit for a unit name ("m", "mm", "um", "µm", "nm"); throws InputError.
double unit_scale(const std::string& unit, const std::string& source);

}  // namespace wr
