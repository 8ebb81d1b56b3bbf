#pragma once
// A rigid periodic obstacle given by a height map, triangulated on its lattice (each cell
// split along the diagonal from (i, j) to (i+1, j+1), thesis sec. 4.2.3), with the ray casting
// that measures normal gaps: a ray's xy projection is walked cell by cell through the lattice
// (Amanatides-Woo traversal, the continuous form of the thesis's Bresenham walk), and only the
// two triangles of each visited cell are tested (Moller-Trumbore). The obstacle repeats with
// periods Lx = nx dx, Ly = ny dy; no copy is made.
#include <optional>
#include <vector>

#include "lib/core/height_map.hpp"
#include "lib/core/vec3.hpp"

namespace wr {

struct RayHit {
  double t = 0;      // signed distance along the (unit) direction: > 0 ahead, < 0 behind
  Vec3 point;        // m
  Vec3 normal;       // unit upward contact normal at the hit (see contact_normal)
};

class PeriodicObstacle {
 public:
  explicit PeriodicObstacle(const HeightMap& surface);  // periodic map, heights in m

  double lx() const { return nx_ * dx_; }
  double ly() const { return ny_ * dy_; }
  // Height of the triangulated surface at (x, y), any x, y (periodic).
  double height(double x, double y) const;
  // Upward unit normal of the triangle under (x, y).
  Vec3 normal(double x, double y) const;
  double max_height() const { return max_h_; }
  // Normal used for contact at a surface point q: the barycentric blend of the vertex normals
  // of the triangle under q (each vertex normal the angle-weighted mean of the triangles
  // around it). Unlike the piecewise-constant triangle normals it varies continuously with q,
  // which keeps the damped Signorini iteration from cycling between triangles; the gap
  // itself is measured to the exact triangulated surface.
  Vec3 contact_normal(const Vec3& q) const;
  // The triangle's own normal inside it, blended into contact_normal() within `band` (a
  // fraction of the barycentric range, (0, 1]) of its edges: the exact frictionless force
  // direction on the facets, continuous across edges and vertices (there it lies in the
  // normal cone of the kink), so the Signorini iteration does not cycle between facets.
  Vec3 banded_facet_normal(const Vec3& q, double band) const;
  // Angle-weighted normal at lattice vertex (i, j).
  Vec3 vertex_normal(long i, long j) const;

  // Where the line p + t d enters the obstacle (going along d from free space into it) nearest
  // to p; d need not be unit, t is reported in units of |d|. For p outside (above the surface)
  // that is the first crossing ahead, t in [0, max_distance]; none if there is none within it.
  // For p inside (below the surface) it is the first crossing behind, t < 0 (the signed gap of
  // a penetrating point), within max_distance; when d points down (d.z < 0) it is always
  // found, the line being out above the highest point at the latest.
  std::optional<RayHit> cast(const Vec3& p, const Vec3& d, double max_distance) const;

 private:
  std::size_t wrap_index(long i, long j) const;  // lattice index with periodic wrap
  double h(long i, long j) const;                 // lattice height with periodic wrap
  // First hit along p + t d for t in [0, tmax] (d unit); walks the cells.
  std::optional<RayHit> cast_forward(const Vec3& p, const Vec3& d, double tmax) const;
  bool hit_cell(long ci, long cj, const Vec3& p, const Vec3& d, double tmax, RayHit& best) const;

  std::size_t nx_, ny_;
  double dx_, dy_;
  BigVector z_;
  std::vector<Vec3> vertex_normals_;
  double max_h_ = 0;
};

// The obstacle sampled on a lattice `refine` times finer (1 ... 16), heights of the same
// triangulated surface: the spectral model's counterpart of the FEM face lattice (obstacle
// spacing / refine). Periodic in, periodic out.
HeightMap resample_triangulated(const HeightMap& surface, int refine);

}  // namespace wr
