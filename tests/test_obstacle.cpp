// Periodic triangulated obstacle: interpolation, normals, and ray casting against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "lib/contact/periodic_obstacle.hpp"
#include "lib/contact/smooth_obstacle.hpp"

namespace wr {
namespace {

HeightMap random_map(std::size_t nx, std::size_t ny, std::uint64_t seed, double amp) {
  HeightMap m(nx, ny, 1e-4, 2e-4);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (double& v : m.h) v = u(rng);
  return m;
}

TEST(Obstacle, InterpolatesLatticeValuesAndIsPeriodic) {
  const HeightMap m = random_map(7, 5, 1, 1e-4);
  const PeriodicObstacle o(m);
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t i = 0; i < 7; ++i) {
      EXPECT_DOUBLE_EQ(o.height(i * 1e-4, j * 2e-4), m(i, j));
      EXPECT_NEAR(o.height(i * 1e-4 + o.lx(), j * 2e-4 - 3 * o.ly()), m(i, j), 1e-18);
    }
  // Inside a cell the surface is linear on each triangle: the mid-point of the diagonal.
  EXPECT_NEAR(o.height(0.5e-4, 1e-4), 0.5 * (m(0, 0) + m(1, 1)), 1e-18);
}

// The C2 spline obstacle passes through every lattice height and repeats with the map's periods,
// values and derivatives alike.
TEST(SmoothObstacle, InterpolatesLatticeValuesAndIsPeriodic) {
  const HeightMap m = random_map(7, 5, 1, 1e-4);
  const SmoothObstacle o(m);
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t i = 0; i < 7; ++i) EXPECT_NEAR(o.height(i * 1e-4, j * 2e-4), m(i, j), 1e-16);
  for (double x : {0.13e-4, 3.71e-4}) {
    const auto a = o.at(x, 1.3e-4), b = o.at(x - 2 * o.lx(), 1.3e-4 + o.ly());
    EXPECT_NEAR(a.h, b.h, 1e-16);
    EXPECT_NEAR(a.hx, b.hx, 1e-12);
    EXPECT_NEAR(a.hyy, b.hyy, 1e-6);
  }
  EXPECT_GE(o.max_height(), *std::max_element(m.h.begin(), m.h.end()) - 1e-16);
}

// On h = A sin(kx x) cos(ky y), 32 and 16 samples per period, the spline and its derivatives
// against the analytic ones at points between the samples. A cubic spline's error is of order
// (k dx)^4 in the value, (k dx)^3 in the slope and (k dx)^2 in the curvature, relative to the
// amplitude of each: here (2 pi / 32)^2 = 4 % for the curvature; the bars sit above the
// measured errors (6.4e-5, 3.8e-4, 6.1e-3 of the amplitudes, printed) about tenfold.
TEST(SmoothObstacle, ReproducesASinusoidAndItsDerivatives) {
  const std::size_t nx = 32, ny = 16;
  const double dx = 1e-4, dy = 2e-4, A = 3e-5;
  const double kx = 2 * M_PI / (nx * dx), ky = 2 * M_PI / (ny * dy);
  HeightMap m(nx, ny, dx, dy);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) m(i, j) = A * std::sin(kx * i * dx) * std::cos(ky * j * dy);
  const SmoothObstacle o(m);
  double e_h = 0, e_g = 0, e_c = 0;
  for (double x = 0.37 * dx; x < nx * dx; x += 1.13 * dx)
    for (double y = 0.61 * dy; y < ny * dy; y += 0.87 * dy) {
      const auto s = o.at(x, y);
      const double sx = std::sin(kx * x), cx = std::cos(kx * x), sy = std::sin(ky * y), cy = std::cos(ky * y);
      e_h = std::max(e_h, std::abs(s.h - A * sx * cy) / A);
      e_g = std::max({e_g, std::abs(s.hx - A * kx * cx * cy) / (A * kx), std::abs(s.hy + A * ky * sx * sy) / (A * kx)});
      e_c = std::max({e_c, std::abs(s.hxx + A * kx * kx * sx * cy) / (A * kx * kx),
                      std::abs(s.hxy + A * kx * ky * cx * sy) / (A * kx * kx),
                      std::abs(s.hyy + A * ky * ky * sx * cy) / (A * kx * kx)});
    }
  std::printf("spline errors: value %.2e slope %.2e curvature %.2e\n", e_h, e_g, e_c);
  EXPECT_LT(e_h, 1e-3);
  EXPECT_LT(e_g, 4e-3);
  EXPECT_LT(e_c, 6e-2);
}

// The banded facet normal is the triangle's own normal away from its edges and the smooth
// contact normal on them, so it is continuous across edges.
TEST(Obstacle, BandedFacetNormalIsTheFacetInsideAndTheBlendOnEdges) {
  const HeightMap m = random_map(6, 6, 3, 1e-4);
  const PeriodicObstacle o(m);
  // Lower triangle of cell (2, 3): barycentric weights (1-u, u-v, v).
  const double dx = 1e-4, dy = 2e-4;
  const Vec3 centroid{(2 + 2.0 / 3) * dx, (3 + 1.0 / 3) * dy, 0};
  const Vec3 f = o.normal(centroid.x, centroid.y), b = o.banded_facet_normal(centroid, 0.25);
  EXPECT_NEAR((f - b).norm(), 0.0, 1e-12);
  const Vec3 on_edge{(2 + 0.5) * dx, (3 + 0.5) * dy, 0};  // the cell's diagonal
  const Vec3 be = o.banded_facet_normal(on_edge, 0.25), ce = o.contact_normal(on_edge);
  EXPECT_NEAR((be - ce).norm(), 0.0, 1e-12);
  // Just either side of the diagonal: nearly the same normal (continuity), unlike the facets'.
  const Vec3 lo{on_edge.x + 1e-9 * dx, on_edge.y, 0}, hi{on_edge.x - 1e-9 * dx, on_edge.y, 0};
  EXPECT_LT((o.banded_facet_normal(lo, 0.25) - o.banded_facet_normal(hi, 0.25)).norm(), 1e-6);
  EXPECT_GT((o.normal(lo.x, lo.y) - o.normal(hi.x, hi.y)).norm(), 1e-3);
}

TEST(Obstacle, PlaneHasExactNormalsAndVerticalGaps) {
  // A plane z = 0.2 x + 0.1 y is linear on every triangle (test away from the seam).
  HeightMap m(20, 20, 1e-4, 1e-4);
  for (std::size_t j = 0; j < 20; ++j)
    for (std::size_t i = 0; i < 20; ++i) m(i, j) = 0.2 * i * 1e-4 + 0.1 * j * 1e-4;
  const PeriodicObstacle o(m);
  const Vec3 n = o.normal(5.3e-4, 7.1e-4);
  const Vec3 expect = Vec3{-0.2, -0.1, 1}.unit();
  EXPECT_NEAR(n.x, expect.x, 1e-12);
  EXPECT_NEAR(n.y, expect.y, 1e-12);
  EXPECT_NEAR(n.z, expect.z, 1e-12);
  const Vec3 p{5.3e-4, 7.1e-4, 1e-3};
  const auto hit = o.cast(p, Vec3{0, 0, -1}, 1.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 1e-3 - (0.2 * 5.3e-4 + 0.1 * 7.1e-4), 1e-15);
  // Along the surface normal the distance is the perpendicular distance to the plane.
  const auto hn = o.cast(p, expect * -1.0, 1.0);
  ASSERT_TRUE(hn);
  const double perp = (1e-3 - 0.2 * 5.3e-4 - 0.1 * 7.1e-4) / std::sqrt(1 + 0.04 + 0.01);
  EXPECT_NEAR(hn->t, perp, 1e-15);
  // A point below the surface: the hit is behind (negative t), i.e. penetration.
  const auto below = o.cast(Vec3{5.3e-4, 7.1e-4, 0.0}, Vec3{0, 0, -1}, 1.0);
  ASSERT_TRUE(below);
  EXPECT_LT(below->t, 0);
}

// Oblique rays over a rough periodic surface, crossing the seams: the reported hit lies on the
// surface and is the first sign change of z - h along the ray (fine brute-force march).
TEST(Obstacle, ObliqueRaysFindTheFirstCrossingAcrossSeams) {
  const HeightMap m = random_map(16, 12, 7, 1e-4);
  const PeriodicObstacle o(m);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(-o.lx(), 2 * o.lx()), uy(-o.ly(), 2 * o.ly()), ud(-1, 1);
  int tested = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 p{ux(rng), uy(rng), 3e-4};
    const Vec3 d = Vec3{ud(rng), ud(rng), -0.3 - std::abs(ud(rng))}.unit();
    const auto hit = o.cast(p, d, 0.05);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->point.z, o.height(hit->point.x, hit->point.y), 1e-12);
    // March from p in steps of 1e-7 m until z drops below the surface.
    double t = 0;
    while (p.z + d.z * t - o.height(p.x + d.x * t, p.y + d.y * t) > 0) t += 1e-7;
    EXPECT_NEAR(hit->t, t, 1.1e-7);
    ++tested;
  }
  EXPECT_EQ(tested, 300);
}

// The gap is where the line through a point enters the obstacle: ahead of a point outside,
// behind a point inside, even when the other way meets the surface sooner. Scene: a periodic V
// valley of slope 3 across x (bottom at x = 1 mm, peaks at 0 and 2 mm), a ray down and +x at
// 45 degrees. From a point 10 um above the left flank the line meets that flank 5 um behind
// (an exit: that plane would hold the point off an asperity it is not pressing on) and enters
// the right flank ahead; from a point 10 um inside the left flank it leaves it 5 um ahead and
// came in over the peak behind. Checked against a fine march along the line.
TEST(Obstacle, GapIsTheEntryCrossingOnTheSideThePointIsOn) {
  const double dx = 1e-4;
  HeightMap m(20, 4, dx, dx);
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 20; ++i) m(i, j) = 3.0 * std::abs(double(i) - 10.0) * dx;
  const PeriodicObstacle o(m);
  const Vec3 d = Vec3{1, 0, -1}.unit();
  // First t (step 1e-8 m, either sign of `dir`) where z - h changes sign from p's side.
  const auto march = [&](const Vec3& p, double dir) {
    const bool outside = p.z > o.height(p.x, p.y);
    double t = 0;
    for (;;) {
      const Vec3 q = p + d * t;
      if ((q.z > o.height(q.x, q.y)) != outside) return t;
      t += dir * 1e-8;
    }
  };
  const Vec3 above{0.8e-3, 1.5e-4, 0.6e-3 + 1e-5}, inside{0.8e-3, 1.5e-4, 0.6e-3 - 1e-5};
  EXPECT_NEAR(march(above, -1), -5e-6 * std::sqrt(2.0), 2e-8);  // the nearer crossing, behind
  const auto a = o.cast(above, d, 0.05);
  ASSERT_TRUE(a);
  EXPECT_GT(a->t, 0);
  EXPECT_NEAR(a->t, march(above, +1), 2e-8);
  EXPECT_GT(a->point.x, 1e-3);  // on the right flank
  EXPECT_NEAR(a->point.z, o.height(a->point.x, a->point.y), 1e-15);

  EXPECT_NEAR(march(inside, +1), 5e-6 * std::sqrt(2.0), 2e-8);  // the nearer crossing, ahead
  const auto b = o.cast(inside, d, 0.05);
  ASSERT_TRUE(b);
  EXPECT_LT(b->t, 0);
  EXPECT_NEAR(b->t, march(inside, -1), 2e-8);
  EXPECT_NEAR(b->point.z, o.height(b->point.x, b->point.y), 1e-15);
  // Inside, a downward line always finds its way out, however short the search asked for.
  const auto c = o.cast(inside, d, 1e-9);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->t, b->t, 1e-15);
}

TEST(Obstacle, FarObstacleIsNotFound) {
  const HeightMap m = random_map(8, 8, 2, 1e-5);
  const PeriodicObstacle o(m);
  EXPECT_FALSE(o.cast(Vec3{1e-4, 1e-4, 1.0}, Vec3{0, 0, -1}, 0.5));
  EXPECT_TRUE(o.cast(Vec3{1e-4, 1e-4, 1.0}, Vec3{0, 0, -1}, 1.5));
}

// Resampling onto a finer lattice keeps the triangulated surface: the lattice heights come
// back at every refine-th sample, and inside a triangle the value is the plane through its
// three corners (here checked at the cell centre of the lower-left triangle's diagonal and at
// a point of the upper triangle). Periodic in, periodic out.
TEST(Obstacle, ResamplingKeepsTheTriangulatedSurface) {
  HeightMap m(4, 3, 1e-3, 2e-3);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 4; ++i) m(i, j) = 1e-4 * double((i * 7 + j * 3) % 5);
  const HeightMap f = resample_triangulated(m, 4);
  ASSERT_EQ(f.nx, 16u);
  ASSERT_EQ(f.ny, 12u);
  EXPECT_DOUBLE_EQ(f.dx, 2.5e-4);
  EXPECT_TRUE(f.periodic);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(f(4 * i, 4 * j), m(i, j), 1e-15);
  // Cell (0, 0): lower triangle (u >= v) through (0,0), (1,0), (1,1); at u = 0.5, v = 0.25:
  const double lower = m(0, 0) + 0.5 * (m(1, 0) - m(0, 0)) + 0.25 * (m(1, 1) - m(1, 0));
  EXPECT_NEAR(f(2, 1), lower, 1e-15);
  // Upper triangle (u < v) through (0,0), (1,1), (0,1); at u = 0.25, v = 0.75:
  const double upper = m(0, 0) + 0.75 * (m(0, 1) - m(0, 0)) + 0.25 * (m(1, 1) - m(0, 1));
  EXPECT_NEAR(f(1, 3), upper, 1e-15);
  // The last cell wraps to the first column and row.
  const double wrap = m(3, 2) + 0.5 * (m(0, 2) - m(3, 2)) + 0.5 * (m(0, 0) - m(0, 2));
  EXPECT_NEAR(f(14, 10), wrap, 1e-15);
  EXPECT_THROW(resample_triangulated(m, 0), std::invalid_argument);
}

}  // namespace
}  // namespace wr
