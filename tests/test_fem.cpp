// FEM contact solver: exact cases. Runs under MPI too (ctest runs it on 1 and 2 ranks).
#include <gtest/gtest.h>

#include <cmath>

#include "lib/fem/elastic_block.hpp"
#include "lib/fem/petsc_session.hpp"

namespace wr {
namespace {

// A flat obstacle and a frictionless top: uniaxial compression, Fz = E A dz / Lz exactly
// (trilinear elements represent the uniform strain state), whatever the grading.
TEST(Fem, UniaxialCompressionOnAFlatObstacle) {
  for (double grading : {1.0, 2.0}) {
    BlockSpec b;
    b.lx = 0.03;
    b.ly = 0.02;
    b.lz = 0.025;
    b.nx = 6;
    b.ny = 5;
    b.nz = 7;
    b.grading = grading;
    b.young = 3.0e6;
    b.poisson = 0.45;
    ElasticBlock block(b);
    ContactLoad load;
    load.uz = 1e-4;
    load.top = TopCondition::frictionless;
    load.ksp_rtol = 1e-13;
    load.tolerance = 1e-12;
    const ContactSolution s = block.solve(load);
    ASSERT_TRUE(s.converged) << s.message;
    const double expected = b.young * b.lx * b.ly * load.uz / b.lz;
    EXPECT_NEAR(s.fz / expected, 1.0, 1e-8) << "grading " << grading;
    EXPECT_NEAR(s.fx / expected, 0.0, 1e-8);
    EXPECT_EQ(s.contact_nodes, s.face_nodes);
    EXPECT_LT(s.max_penetration, 1e-12);
  }
}

// A paraboloid cap (radius of curvature 5 cm) at the centre of the period, shifted so that
// its top touches z = 0.
HeightMap cap_map(std::size_t n, double L) {
  HeightMap m(n, n, L / n, L / n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double x = i * L / n - L / 2, y = j * L / n - L / 2;
      m(i, j) = -(x * x + y * y) / (2 * 0.05);
    }
  return m;
}

// Partial contact: no node penetrates, and pressing harder presses more area; following the
// geometry (rays, rotated normals) and the vertical linearisation agree for this gentle cap.
TEST(Fem, PartialContactOnACapIsAdmissible) {
  BlockSpec b;
  b.nx = b.ny = 12;
  b.nz = 6;
  b.grading = 1.5;
  const PeriodicObstacle cap(cap_map(48, 0.03));
  for (bool follow : {false, true}) {
    ElasticBlock block(b);
    ContactLoad load;
    load.obstacle = &cap;
    load.follow_geometry = follow;
    std::size_t last = 0;
    double fz_last = 0;
    for (double uz : {2e-5, 1e-4, 4e-4}) {
      load.uz = uz;
      const ContactSolution s = block.solve(load);
      ASSERT_TRUE(s.converged) << s.message;
      EXPECT_LT(s.max_penetration, 1e-3 * uz);
      EXPECT_GT(s.fz, fz_last);
      EXPECT_GE(s.contact_nodes, last);
      EXPECT_LT(s.contact_nodes, s.face_nodes);
      EXPECT_NEAR(s.fx, 0.0, 0.02 * s.fz);  // symmetric cap: no shear beyond discretisation noise
      last = s.contact_nodes;
      fz_last = s.fz;
    }
  }
}

// A ratchet (sawtooth rising gently along +x, slope 0.2, dropping steeply) under normal load:
// the block rests on the gentle faces, whose normals lean against +x, so holding the top in
// place takes a tangential force along +x, below 0.2 Fz (the contact normals blend towards
// the steep faces near the tips); the mirrored ratchet gives the mirrored force. The vertical
// linearisation (no rotated normals) cannot see it and gives Fx = 0.
TEST(Fem, RatchetObstaclePushesAlongItsGentleFaces) {
  BlockSpec b;
  b.nx = 32;
  b.ny = 4;
  b.nz = 8;
  b.grading = 1.5;
  const std::size_t n = 64;
  const double L = 0.03, dx = L / n, slope = 0.2;
  double mu_follow[2] = {0, 0};
  for (int dir : {+1, -1}) {
    HeightMap w(n, n, dx, dx);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        // 16 cells per tooth; the tips (odd i) fall between the block's nodes (every 2 cells)
        // for both orientations, so the two cases are mirror images of each other.
        const std::size_t k = dir > 0 ? i % 16 : 15 - (i + 1) % 16;
        w(i, j) = slope * dx * double(k);
      }
    const PeriodicObstacle ob(w);
    for (bool follow : {true, false}) {
      ElasticBlock block(b);
      ContactLoad load;
      load.obstacle = &ob;
      load.follow_geometry = follow;
      load.uz = 1e-3;
      const ContactSolution s = block.solve(load);
      ASSERT_TRUE(s.converged) << s.message;
      const double mu = s.fx / s.fz;
      if (follow) {
        EXPECT_LT(s.max_penetration, 1e-8);  // nodes stay on the obstacle (1e-5 of the press)
        EXPECT_GT(dir * mu, 0.03) << "dir " << dir;
        EXPECT_LT(dir * mu, 0.2 + 1e-9) << "dir " << dir;
        mu_follow[dir > 0 ? 0 : 1] = mu;
      } else {
        EXPECT_NEAR(mu, 0.0, 1e-6);  // and nodes pushed sideways penetrate: why Algorithm 1 exists
        EXPECT_GT(s.max_penetration, 1e-6);
      }
    }
  }
  // Mirror images within the discretisation's asymmetry (the cell diagonals are not mirrored).
  EXPECT_NEAR(mu_follow[0], -mu_follow[1], 0.1 * mu_follow[0]);
}

}  // namespace
}  // namespace wr

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  wr::PetscSession petsc(&argc, &argv);
  return RUN_ALL_TESTS();
}
