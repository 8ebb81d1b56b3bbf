#include "lib/contact/smooth_obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wr {
namespace {

// In place, along a periodic line of n values with stride `stride`: the coefficients c of the
// cubic B-spline that interpolates s, (c[k-1] + 4 c[k] + c[k+1]) / 6 = s[k]. The inverse
// filter 6 / (z + 4 + 1/z) = -6 z1 / ((1 - z1/z)(1 - z1 z)), z1 = sqrt(3) - 2, runs as one
// causal and one anti-causal recursion (Unser, Aldroubi & Eden 1991), each started with its
// exact periodic sum.
void interpolating_coefficients(double* s, std::size_t n, std::size_t stride) {
  const double z1 = std::sqrt(3.0) - 2.0;
  const double wrap = 1.0 / (1.0 - std::pow(z1, double(n)));
  auto at = [&](std::size_t k) -> double& { return s[k * stride]; };
  double start = 0, zk = 1;
  for (std::size_t m = 0; m < n; ++m, zk *= z1) start += zk * at((n - m) % n);
  std::vector<double> cp(n);
  cp[0] = start * wrap;
  for (std::size_t k = 1; k < n; ++k) cp[k] = at(k) + z1 * cp[k - 1];
  double end = 0;
  zk = 1;
  for (std::size_t m = 0; m < n; ++m, zk *= z1) end += zk * cp[(n - 1 + m) % n];
  double cm = end * wrap;
  at(n - 1) = -6.0 * z1 * cm;
  for (std::size_t k = n - 1; k-- > 0;) {
    cm = cp[k] + z1 * cm;
    at(k) = -6.0 * z1 * cm;
  }
}

// The four cubic B-spline weights at offset t in [0, 1) of a cell, and their first and second
// derivatives with respect to t; they multiply the coefficients of points i-1 ... i+2.
struct Weights {
  double w[4], d1[4], d2[4];
  explicit Weights(double t) {
    const double u = 1 - t, t2 = t * t, t3 = t2 * t;
    w[0] = u * u * u / 6;
    w[1] = (3 * t3 - 6 * t2 + 4) / 6;
    w[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
    w[3] = t3 / 6;
    d1[0] = -u * u / 2;
    d1[1] = (3 * t2 - 4 * t) / 2;
    d1[2] = (-3 * t2 + 2 * t + 1) / 2;
    d1[3] = t2 / 2;
    d2[0] = u;
    d2[1] = 3 * t - 2;
    d2[2] = 1 - 3 * t;
    d2[3] = t;
  }
};

// Cell index (wrapped into [0, n)) and offset in it of coordinate x on spacing d.
void locate(double x, double d, std::size_t n, long& i, double& t) {
  const double s = x / d;
  const double f = std::floor(s);
  t = s - f;
  const long nl = long(n);
  i = long(std::fmod(f, double(nl)));
  if (i < 0) i += nl;
}

}  // namespace

SmoothObstacle::SmoothObstacle(const HeightMap& surface)
    : nx_(surface.nx), ny_(surface.ny), dx_(surface.dx), dy_(surface.dy), c_(surface.h.begin(), surface.h.end()) {
  if (!surface.periodic) throw std::invalid_argument("SmoothObstacle: the surface must be periodic");
  if (nx_ < 4 || ny_ < 4) throw std::invalid_argument("SmoothObstacle: at least 4 x 4 points");
  for (std::size_t j = 0; j < ny_; ++j) interpolating_coefficients(c_.data() + j * nx_, nx_, 1);
  for (std::size_t i = 0; i < nx_; ++i) interpolating_coefficients(c_.data() + i, ny_, nx_);
}

SmoothObstacle::Local SmoothObstacle::at(double x, double y) const {
  long i, j;
  double tx, ty;
  locate(x, dx_, nx_, i, tx);
  locate(y, dy_, ny_, j, ty);
  const Weights wx(tx), wy(ty);
  const long nx = long(nx_), ny = long(ny_);
  Local o;
  for (int b = 0; b < 4; ++b) {
    const long jj = (j + b - 1 + ny) % ny;
    const double* row = c_.data() + std::size_t(jj) * nx_;
    double r = 0, rx = 0, rxx = 0;
    for (int a = 0; a < 4; ++a) {
      const double c = row[std::size_t((i + a - 1 + nx) % nx)];
      r += wx.w[a] * c;
      rx += wx.d1[a] * c;
      rxx += wx.d2[a] * c;
    }
    o.h += wy.w[b] * r;
    o.hx += wy.w[b] * rx;
    o.hy += wy.d1[b] * r;
    o.hxx += wy.w[b] * rxx;
    o.hxy += wy.d1[b] * rx;
    o.hyy += wy.d2[b] * r;
  }
  o.hx /= dx_;
  o.hy /= dy_;
  o.hxx /= dx_ * dx_;
  o.hxy /= dx_ * dy_;
  o.hyy /= dy_ * dy_;
  return o;
}

double SmoothObstacle::max_height() const {
  constexpr int kSub = 4;
  double m = -INFINITY;
  for (std::size_t j = 0; j < ny_ * kSub; ++j)
    for (std::size_t i = 0; i < nx_ * kSub; ++i)
      m = std::max(m, height(double(i) * dx_ / kSub, double(j) * dy_ / kSub));
  return m;
}

}  // namespace wr
