// Richardson extrapolation (lib/core/richardson.hpp) on sequences with a known limit.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "lib/core/richardson.hpp"

namespace wr {
namespace {

// f(h) = L + C h^p sampled at h, h / r, h / r^2 is extrapolated exactly: the limit L, the order
// p, and the GCI 1.25 |f1 - f2| / (r^p - 1), which here is 1.25 times the finest error.
TEST(Richardson, PowerLawSequencesGiveTheirLimitAndOrder) {
  for (double p : {1.0, 2.0, 2.6})
    for (double r : {2.0, 3.0}) {
      const double L = 0.0038, C = 0.004;
      const auto f = [&](double h) { return L + C * std::pow(h, p); };
      const auto e = richardson_three(f(1), f(1 / r), f(1 / (r * r)), r);
      ASSERT_TRUE(e.has_value()) << "p " << p << ", r " << r;
      EXPECT_NEAR(e->order, p, 1e-9);
      EXPECT_NEAR(e->limit, L, 1e-14);
      EXPECT_NEAR(e->error, 1.25 * std::abs(f(1 / (r * r)) - L), 1e-14);
    }
}

// Differences that grow or change sign are outside the asymptotic range: no limit claimed.
TEST(Richardson, NonConvergingSequencesAreRefused) {
  EXPECT_FALSE(richardson_three(1.0, 1.1, 1.3).has_value());   // growing differences
  EXPECT_FALSE(richardson_three(1.0, 1.2, 1.1).has_value());   // oscillating
  EXPECT_FALSE(richardson_three(1.0, 2.0, 2.0).has_value());   // stops dead after a jump
  EXPECT_FALSE(richardson_three(1.0, NAN, 2.0).has_value());   // an unfinished mesh
  const auto same = richardson_three(0.5, 0.5, 0.5);
  ASSERT_TRUE(same.has_value());
  EXPECT_EQ(same->limit, 0.5);
  EXPECT_EQ(same->error, 0.0);
  EXPECT_THROW(richardson_three(1.0, 0.5, 0.25, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace wr
