#pragma once
// Neighbourhoods of a grid cell for water routing: 4- or 8-connectivity, on a torus (periodic
// surface: a neighbour across the seam lies in the next tile of the infinite periodic plane)
// or on a bounded map (a neighbour outside is the outlet).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace wr {

enum class Boundary { torus, outlet };

struct Neighbour {
  std::uint32_t cell;  // index iy*nx + ix of the neighbour (undefined when outside)
  std::int8_t sx, sy;  // tile shift of the neighbour's copy adjacent to the cell (torus)
  bool outside;        // bounded maps: the neighbour is beyond the edge (the outlet)
  double distance;     // in units of the grid spacing along the step (1 or sqrt(2) for dx = dy)
};

class GridTopology {
 public:
  GridTopology(std::size_t nx, std::size_t ny, double dx, double dy, int connectivity, Boundary b)
      : nx_(nx), ny_(ny), conn_(connectivity), boundary_(b) {
    const int d[8][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    for (int k = 0; k < 8; ++k) {
      step_[k][0] = d[k][0];
      step_[k][1] = d[k][1];
      dist_[k] = std::hypot(d[k][0] * dx, d[k][1] * dy);
    }
  }
  std::size_t nx() const { return nx_; }
  std::size_t ny() const { return ny_; }
  std::size_t cells() const { return nx_ * ny_; }
  int connectivity() const { return conn_; }
  Boundary boundary() const { return boundary_; }

  // Neighbour k (0 <= k < connectivity) of cell (ix, iy). Directions are in a fixed order
  // (E, N, W, S, then the diagonals), so every tie broken by direction is shift-invariant.
  Neighbour neighbour(std::size_t ix, std::size_t iy, int k) const {
    long jx = static_cast<long>(ix) + step_[k][0], jy = static_cast<long>(iy) + step_[k][1];
    Neighbour n{0, 0, 0, false, dist_[k]};
    const long lx = static_cast<long>(nx_), ly = static_cast<long>(ny_);
    if (jx < 0 || jx >= lx || jy < 0 || jy >= ly) {
      if (boundary_ == Boundary::outlet) {
        n.outside = true;
        return n;
      }
      n.sx = static_cast<std::int8_t>(jx < 0 ? -1 : (jx >= lx ? 1 : 0));
      n.sy = static_cast<std::int8_t>(jy < 0 ? -1 : (jy >= ly ? 1 : 0));
      jx -= n.sx * lx;
      jy -= n.sy * ly;
    }
    n.cell = static_cast<std::uint32_t>(jy * lx + jx);
    return n;
  }

 private:
  std::size_t nx_, ny_;
  int conn_;
  Boundary boundary_;
  int step_[8][2];
  double dist_[8];
};

}  // namespace wr
