#include "lib/analytic/hertz.hpp"

#include <cmath>

namespace wr {

HeightMap paraboloid_cap(std::size_t n, double period, double radius) {
  const double dx = period / double(n);
  HeightMap m(n, n, dx, dx);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double x = double(i) * period / double(n) - period / 2, y = double(j) * period / double(n) - period / 2;
      m(i, j) = -(x * x + y * y) / (2 * radius);
    }
  return m;
}

double hertz_radius(double force, double radius, double e_star) { return std::cbrt(3 * force * radius / (4 * e_star)); }

double hertz_force(double contact_radius, double radius, double e_star) {
  return 4 * e_star * contact_radius * contact_radius * contact_radius / (3 * radius);
}

HertzFit fit_hertz_pressure(std::span<const double> pressure, int nx, int ny, double h, double cx, double cy,
                            double a_guess, double inner) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int cnt = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double p = pressure[std::size_t(j) * nx + i];
      const double r2 = std::pow(i * h - cx, 2) + std::pow(j * h - cy, 2);
      if (!(p > 0) || r2 > inner * a_guess * a_guess) continue;
      sx += r2;
      sy += p * p;
      sxx += r2 * r2;
      sxy += r2 * p * p;
      ++cnt;
    }
  HertzFit f;
  f.points = cnt;
  if (cnt < 3) return f;
  const double slope = (cnt * sxy - sx * sy) / (cnt * sxx - sx * sx), icpt = (sy - slope * sx) / cnt;
  if (!(slope < 0) || !(icpt > 0)) return f;
  f.radius = std::sqrt(-icpt / slope);
  f.peak_pressure = std::sqrt(icpt);
  f.ok = true;
  return f;
}

}  // namespace wr
