// The FEM shear test's adaptive phase (ContactTestOptions::to_peak): the step controller, and a
// block sheared over ridges until its friction curve turns over. Runs on 1 and 2 ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <petscsys.h>

#include "lib/fem/block_press_shear.hpp"
#include "roads/height_stats.hpp"

namespace wr {
namespace {

TEST(ShearToPeak, StepsFollowTheLastStepsWorkWithinBounds) {
  const double first = 1e-3;
  EXPECT_DOUBLE_EQ(adapt_shear_step(first, 10, 40, first), first);        // easier: never longer
  EXPECT_DOUBLE_EQ(adapt_shear_step(first, 80, 40, first), first);        // up to twice as hard: the same
  EXPECT_DOUBLE_EQ(adapt_shear_step(first, 81, 40, first), 0.5 * first);  // over twice as hard: shorter
  EXPECT_DOUBLE_EQ(adapt_shear_step(first / 7, 300, 40, first), first / 8);
}

// Saw-tooth ridges across a 3 cm block (4 teeth, faces of slope 0.2 falling along x, then a
// one-cell rise): sheared along x, mu rises (measured: 0.07 pressed, then 0.14, 0.22, 0.27 at
// 1.25, 2.5, 3.75 mm) and falls (0.11 at 5 mm) when the contact passes the teeth. With to_peak
// the run ends at that first lower step, long before ux = L / 2.
TEST(ShearToPeak, EndsWhenTheFrictionCurveTurnsOver) {
  const std::size_t n = 32, tooth = 8;
  const double L = 0.03, dx = L / n, slope = 0.2;
  HeightMap ridges(n, n, dx, dx);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) ridges(i, j) = slope * dx * double(tooth - 1 - i % tooth);
  ContactTestOptions o;
  o.shear = true;
  o.uz = 1e-3;
  o.normal_steps = 1;
  o.ux = L / 2;
  o.shear_steps = 12;
  o.to_peak = true;
  o.refine = 1;
  o.tolerance = 1e-5;
  o.rms_slope = rms_slope_finite_difference(ridges, 1);
  const ContactTestResult r = run_contact_test(ridges, o, nullptr);
  ASSERT_FALSE(r.failed);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    for (const ContactStep& s : r.steps) std::printf("  ux %.3e  mu %.4f  its %d\n", s.ux, s.mu, s.signorini_iterations);
  ASSERT_GE(r.steps.size(), 4u);
  EXPECT_TRUE(peak_reached(r.steps));
  const ContactStep* peak = peak_friction(r.steps);
  ASSERT_NE(peak, nullptr);
  EXPECT_EQ(peak + 2, r.steps.data() + r.steps.size());  // exactly one step after the peak
  EXPECT_LT(r.steps.back().ux, o.ux);
  EXPECT_GT(peak->mu, 0.05);
  for (const ContactStep* s = r.steps.data() + 2; s <= peak; ++s) EXPECT_GT(s->mu, (s - 1)->mu);
}

}  // namespace
}  // namespace wr
