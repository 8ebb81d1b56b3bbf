#pragma once
// A rigid periodic obstacle as a C2 surface: the periodic bicubic B-spline that interpolates the
// height map at its lattice points. Why: a Newton iteration on the contact condition
// z + u_z >= h(x + u_x, y + u_y) needs a gap whose gradient and curvature exist and agree with
// it everywhere; the triangulated obstacle (PeriodicObstacle, the thesis's sec. 4.2.3) has
// normals that jump across every edge and no curvature in between. The spline passes through
// the measured heights, so the two obstacles agree on the lattice and differ between its points
// by the interpolation (O(dx^4 h'''') for smooth data; on rough data the spline can overshoot
// the samples by a fraction of the local height step).
//
// Units: m. Periodic with Lx = nx dx, Ly = ny dy; any x, y may be asked.
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

class SmoothObstacle {
 public:
  // `surface` must be periodic with nx, ny >= 4 (std::invalid_argument otherwise).
  explicit SmoothObstacle(const HeightMap& surface);

  // Height and its first and second derivatives at (x, y).
  struct Local {
    double h = 0;                      // m
    double hx = 0, hy = 0;             // slopes
    double hxx = 0, hxy = 0, hyy = 0;  // 1/m
  };
  Local at(double x, double y) const;
  double height(double x, double y) const { return at(x, y).h; }
  // The highest point, m, found on a lattice four times finer than the data's (the spline's
  // overshoot between samples is resolved to about 1 % of it).
  double max_height() const;
  double lx() const { return double(nx_) * dx_; }
  double ly() const { return double(ny_) * dy_; }

 private:
  std::size_t nx_, ny_;
  double dx_, dy_;
  std::vector<double> c_;  // B-spline coefficients, row-major like the map
};

}  // namespace wr
