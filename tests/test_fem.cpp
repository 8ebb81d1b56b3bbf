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
    const ContactSolution s = block.solve(load);
    ASSERT_TRUE(s.converged) << s.message;
    const double expected = b.young * b.lx * b.ly * load.uz / b.lz;
    EXPECT_NEAR(s.fz / expected, 1.0, 1e-8) << "grading " << grading;
    EXPECT_NEAR(s.fx / expected, 0.0, 1e-8);
    EXPECT_EQ(s.contact_nodes, s.face_nodes);
    EXPECT_LT(s.max_penetration, 1e-12);
  }
}

// A bump: contact is partial, no node penetrates, and pulling harder presses more area.
TEST(Fem, PartialContactOnABumpIsAdmissible) {
  BlockSpec b;
  b.nx = b.ny = 12;
  b.nz = 6;
  b.grading = 1.5;
  ElasticBlock block(b);
  ContactLoad load;
  load.obstacle = [](double x, double y) {
    const double r2 = (x - 0.015) * (x - 0.015) + (y - 0.015) * (y - 0.015);
    return -r2 / (2 * 0.05);  // paraboloid cap, radius of curvature 5 cm
  };
  std::size_t last = 0;
  for (double uz : {2e-5, 1e-4, 4e-4}) {
    load.uz = uz;
    const ContactSolution s = block.solve(load);
    ASSERT_TRUE(s.converged) << s.message;
    EXPECT_LT(s.max_penetration, 1e-10 * uz / 1e-4);
    EXPECT_GT(s.fz, 0);
    EXPECT_GE(s.contact_nodes, last);
    EXPECT_LT(s.contact_nodes, s.face_nodes);
    last = s.contact_nodes;
  }
}

}  // namespace
}  // namespace wr

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  wr::PetscSession petsc(&argc, &argv);
  return RUN_ALL_TESTS();
}
