#include "lib/contact/periodic_obstacle.hpp"

#include <stdexcept>

#include <algorithm>
#include <cmath>
#include <limits>

namespace wr {
namespace {

long floor_div(double v) { return static_cast<long>(std::floor(v)); }

// Moller-Trumbore: t along p + t d where the line meets triangle (a, b, c); nullopt if it
// misses (or is parallel). Edges shared by two triangles count for both (a tiny tolerance).
std::optional<double> moller_trumbore(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 q = d.cross(e2);
  const double det = e1.dot(q);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const double inv = 1.0 / det;
  const Vec3 s = p - a;
  const double u = s.dot(q) * inv;
  constexpr double eps = 1e-12;
  if (u < -eps || u > 1 + eps) return std::nullopt;
  const Vec3 r = s.cross(e1);
  const double v = d.dot(r) * inv;
  if (v < -eps || u + v > 1 + eps) return std::nullopt;
  return e2.dot(r) * inv;
}

}  // namespace

PeriodicObstacle::PeriodicObstacle(const HeightMap& s)
    : nx_(s.nx), ny_(s.ny), dx_(s.dx), dy_(s.dy), z_(s.h) {
  max_h_ = *std::max_element(z_.begin(), z_.end());
  // Angle-weighted vertex normals: the triangle normals sampled in 8 directions around it.
  vertex_normals_.resize(nx_ * ny_);
  for (std::size_t j = 0; j < ny_; ++j)
    for (std::size_t i = 0; i < nx_; ++i) {
      Vec3 sum;
      for (int k = 0; k < 8; ++k) {
        const double a = (k + 0.5) * M_PI / 4;
        sum = sum + normal(i * dx_ + 1e-6 * dx_ * std::cos(a), j * dy_ + 1e-6 * dy_ * std::sin(a));
      }
      vertex_normals_[j * nx_ + i] = sum.unit();
    }
}

std::size_t PeriodicObstacle::wrap_index(long i, long j) const {
  const long nx = long(nx_), ny = long(ny_);
  i %= nx;
  j %= ny;
  if (i < 0) i += nx;
  if (j < 0) j += ny;
  return std::size_t(j) * nx_ + std::size_t(i);
}

double PeriodicObstacle::h(long i, long j) const { return z_[wrap_index(i, j)]; }

double PeriodicObstacle::height(double x, double y) const {
  const double fx = x / dx_, fy = y / dy_;
  const long i = floor_div(fx), j = floor_div(fy);
  const double u = fx - i, v = fy - j;
  // Lower triangle (u >= v): (i,j), (i+1,j), (i+1,j+1); upper: (i,j), (i+1,j+1), (i,j+1).
  if (u >= v) return h(i, j) + u * (h(i + 1, j) - h(i, j)) + v * (h(i + 1, j + 1) - h(i + 1, j));
  return h(i, j) + v * (h(i, j + 1) - h(i, j)) + u * (h(i + 1, j + 1) - h(i, j + 1));
}

Vec3 PeriodicObstacle::normal(double x, double y) const {
  const double fx = x / dx_, fy = y / dy_;
  const long i = floor_div(fx), j = floor_div(fy);
  double sx, sy;  // surface slopes dz/dx, dz/dy of the triangle
  if (fx - i >= fy - j) {
    sx = (h(i + 1, j) - h(i, j)) / dx_;
    sy = (h(i + 1, j + 1) - h(i + 1, j)) / dy_;
  } else {
    sy = (h(i, j + 1) - h(i, j)) / dy_;
    sx = (h(i + 1, j + 1) - h(i, j + 1)) / dx_;
  }
  return Vec3{-sx, -sy, 1.0}.unit();
}

bool PeriodicObstacle::hit_cell(long ci, long cj, const Vec3& p, const Vec3& d, double tmax, RayHit& best) const {
  const Vec3 a{ci * dx_, cj * dy_, h(ci, cj)};
  const Vec3 b{(ci + 1) * dx_, cj * dy_, h(ci + 1, cj)};
  const Vec3 c{(ci + 1) * dx_, (cj + 1) * dy_, h(ci + 1, cj + 1)};
  const Vec3 e{ci * dx_, (cj + 1) * dy_, h(ci, cj + 1)};
  bool found = false;
  for (int k = 0; k < 2; ++k) {
    const Vec3& q = k == 0 ? b : e;
    const auto t = k == 0 ? moller_trumbore(p, d, a, b, c) : moller_trumbore(p, d, a, c, e);
    if (t && *t >= -1e-15 && *t <= tmax && *t < best.t) {
      best.t = std::max(0.0, *t);
      best.point = p + d * best.t;
      best.normal = ((k == 0 ? (q - a).cross(c - a) : (c - a).cross(q - a))).unit();
      if (best.normal.z < 0) best.normal = best.normal * -1.0;
      found = true;
    }
  }
  return found;
}

std::optional<RayHit> PeriodicObstacle::cast_forward(const Vec3& p, const Vec3& d, double tmax) const {
  RayHit best;
  best.t = std::numeric_limits<double>::infinity();
  long ci = floor_div(p.x / dx_), cj = floor_div(p.y / dy_);
  const int stepx = d.x > 0 ? 1 : -1, stepy = d.y > 0 ? 1 : -1;
  // Parameter t at which the ray crosses the next vertical cell boundary in x and in y.
  const double inf = std::numeric_limits<double>::infinity();
  double tx = std::abs(d.x) < 1e-300 ? inf : (((ci + (stepx > 0)) * dx_) - p.x) / d.x;
  double ty = std::abs(d.y) < 1e-300 ? inf : (((cj + (stepy > 0)) * dy_) - p.y) / d.y;
  const double dtx = std::abs(d.x) < 1e-300 ? inf : dx_ / std::abs(d.x);
  const double dty = std::abs(d.y) < 1e-300 ? inf : dy_ / std::abs(d.y);
  double t_enter = 0;
  while (t_enter <= tmax) {
    hit_cell(ci, cj, p, d, tmax, best);
    // A hit inside this cell's t-range is the first one: later cells lie further along.
    const double t_exit = std::min(tx, ty);
    if (best.t <= t_exit + 1e-15) break;
    if (tx < ty) {
      ci += stepx;
      t_enter = tx;
      tx += dtx;
    } else {
      cj += stepy;
      t_enter = ty;
      ty += dty;
    }
  }
  if (!std::isfinite(best.t)) return std::nullopt;
  return best;
}

Vec3 PeriodicObstacle::vertex_normal(long i, long j) const { return vertex_normals_[wrap_index(i, j)]; }

Vec3 PeriodicObstacle::contact_normal(const Vec3& q) const {
  const double fx = q.x / dx_, fy = q.y / dy_;
  const long i = floor_div(fx), j = floor_div(fy);
  const double u = fx - i, v = fy - j;
  Vec3 n;
  if (u >= v)  // lower triangle (i,j), (i+1,j), (i+1,j+1): weights 1-u, u-v, v
    n = vertex_normal(i, j) * (1 - u) + vertex_normal(i + 1, j) * (u - v) + vertex_normal(i + 1, j + 1) * v;
  else  // upper triangle (i,j), (i+1,j+1), (i,j+1): weights 1-v, u, v-u
    n = vertex_normal(i, j) * (1 - v) + vertex_normal(i + 1, j + 1) * u + vertex_normal(i, j + 1) * (v - u);
  return n.unit();
}

Vec3 PeriodicObstacle::banded_facet_normal(const Vec3& q, double band) const {
  const double fx = q.x / dx_, fy = q.y / dy_;
  const long i = floor_div(fx), j = floor_div(fy);
  const double u = fx - i, v = fy - j;
  // The smallest barycentric weight: 0 on an edge of the triangle, 1/3 at its centroid.
  const double edge = u >= v ? std::min({1 - u, u - v, v}) : std::min({1 - v, u, v - u});
  const double w = std::clamp(edge / band, 0.0, 1.0);
  return (normal(q.x, q.y) * w + contact_normal(q) * (1 - w)).unit();
}

std::optional<RayHit> PeriodicObstacle::cast(const Vec3& p, const Vec3& d, double max_distance) const {
  const double len = d.norm();
  const Vec3 u = d * (1.0 / len);
  std::optional<RayHit> best;
  if (p.z < height(p.x, p.y)) {
    // Inside: the crossing behind p, where the line comes out of the obstacle. The nearest
    // crossing either way can be ahead, where a slightly tilted line leaves a steep flank on
    // its far side; a node held to that plane sits inside the flank at a fixed point of
    // Algorithm 1 (on a 100 x 100 patch of slope 2.8: 1.4e-4 m deep, iteration after
    // iteration). Going back up, the line is out above max_height at the latest.
    const double to_top = u.z < 0 ? (max_h_ - p.z) / -u.z * (1 + 1e-9) + 1e-12 : 0.0;
    best = cast_forward(p, u * -1.0, std::max(max_distance * len, to_top));
    if (best) best->t = -best->t;
  } else {
    // Outside: the first crossing ahead. One behind would be an exit from a neighbouring
    // asperity, a plane that pushes p the wrong way.
    best = cast_forward(p, u, max_distance * len);
  }
  if (best) {
    best->t /= len;
    best->normal = contact_normal(best->point);
  }
  return best;
}

HeightMap resample_triangulated(const HeightMap& surface, int refine) {
  if (refine < 1 || refine > 16) throw std::invalid_argument("refine must be 1 ... 16");
  if (refine == 1) return surface;
  const PeriodicObstacle ob(surface);
  HeightMap fine(surface.nx * std::size_t(refine), surface.ny * std::size_t(refine), surface.dx / refine,
                 surface.dy / refine);
  fine.periodic = true;
  for (std::size_t j = 0; j < fine.ny; ++j)
    for (std::size_t i = 0; i < fine.nx; ++i) fine(i, j) = ob.height(double(i) * fine.dx, double(j) * fine.dy);
  return fine;
}

}  // namespace wr
