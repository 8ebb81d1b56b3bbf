#include "roads/height_stats.hpp"

#include <cmath>

namespace wr {

HeightStats height_stats(const HeightMap& m) {
  HeightStats s;
  const double n = static_cast<double>(m.h.size());
  long double sum = 0;
  for (double v : m.h) sum += v;
  s.mean = static_cast<double>(sum / n);
  long double a = 0, s2 = 0, s3 = 0, s4 = 0;
  for (double v : m.h) {
    const long double d = v - s.mean, d2 = d * d;
    a += std::fabs(static_cast<double>(d));
    s2 += d2;
    s3 += d2 * d;
    s4 += d2 * d2;
  }
  s.sq = std::sqrt(static_cast<double>(s2 / n));
  s.sa = static_cast<double>(a / n);
  if (s.sq > 0) {
    s.ssk = static_cast<double>(s3 / n) / (s.sq * s.sq * s.sq);
    s.sku = static_cast<double>(s4 / n) / (s.sq * s.sq * s.sq * s.sq);
  }
  return s;
}

double rms_slope_finite_difference(const HeightMap& m) {
  const std::size_t nx = m.nx, ny = m.ny;
  const std::size_t ex = m.periodic ? nx : nx - 1;  // number of x differences per row
  long double gx = 0, gy = 0;
  for (std::size_t iy = 0; iy < ny; ++iy)
    for (std::size_t ix = 0; ix < ex; ++ix) {
      const double d = (m(ix + 1 == nx ? 0 : ix + 1, iy) - m(ix, iy)) / m.dx;
      gx += d * d;
    }
  const double mean_gx2 = static_cast<double>(gx / (ex * ny));
  if (m.is_profile()) return std::sqrt(2.0 * mean_gx2);
  const std::size_t ey = m.periodic ? ny : ny - 1;
  for (std::size_t iy = 0; iy < ey; ++iy) {
    const std::size_t jy = iy + 1 == ny ? 0 : iy + 1;
    for (std::size_t ix = 0; ix < nx; ++ix) {
      const double d = (m(ix, jy) - m(ix, iy)) / m.dy;
      gy += d * d;
    }
  }
  return std::sqrt(mean_gx2 + static_cast<double>(gy / (ey * nx)));
}

}  // namespace wr
