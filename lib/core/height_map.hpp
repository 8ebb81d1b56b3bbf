#pragma once
// HeightMap: a surface sampled on a regular grid, the one type every module passes around.
//
// Contract: heights in metres, row-major h[iy*nx + ix] (rows = y, as in the HDF5 files),
// spacings dx, dy > 0 in metres. A profile (one line of a surface) is a HeightMap with
// ny == 1 and kind == Kind::profile. `periodic` says whether the last sample is followed by
// the first one (synthesized surfaces) or the data simply ends (imported measurements).
#include <cstddef>
#include <string>
#include <vector>

#include "lib/core/big_buffer.hpp"

namespace wr {

struct HeightMap {
  enum class Kind { map, profile };

  std::size_t nx = 0;
  std::size_t ny = 0;
  double dx = 0.0;  // m
  double dy = 0.0;  // m (equals dx for a profile)
  bool periodic = true;
  Kind kind = Kind::map;
  BigVector h;  // m; NaN marks a dropout until it is filled

  HeightMap() = default;
  HeightMap(std::size_t nx_, std::size_t ny_, double dx_, double dy_, Kind kind_ = Kind::map)
      : nx(nx_), ny(ny_), dx(dx_), dy(dy_), kind(kind_), h(nx_ * ny_, 0.0) {}

  double& operator()(std::size_t ix, std::size_t iy) { return h[iy * nx + ix]; }
  double operator()(std::size_t ix, std::size_t iy) const { return h[iy * nx + ix]; }

  std::size_t size() const { return h.size(); }
  double lx() const { return static_cast<double>(nx) * dx; }  // period / extent in x, m
  double ly() const { return static_cast<double>(ny) * dy; }  // m
  bool is_profile() const { return kind == Kind::profile; }
};

}  // namespace wr
