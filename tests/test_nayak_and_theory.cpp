// Nayak's summit statistics and the analytic contact predictions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lib/analytic/contact_theory.hpp"
#include "lib/analytic/nayak_summits.hpp"

namespace wr {
namespace {

TEST(Nayak, PdfIsNormalisedForEveryAlpha) {
  for (double alpha : {1.6, 2.0, 7.19, 15.6, 36.5, 88.9, 1000.0}) {
    double s = 0;
    const double h = 1e-3;
    for (double x = -12; x <= 12; x += h) s += nayak_summit_pdf(x, alpha) * h;
    EXPECT_NEAR(s, 1.0, 1e-6) << "alpha " << alpha;
  }
}

TEST(Nayak, MomentsOfEq369AgreeWithGreenwoodEq45) {
  // Integrating eq. 3.69 gives mean 4/sqrt(pi alpha) (Greenwood) and variance 1 - 0.8968/alpha.
  for (double alpha : {2.0, 7.19, 15.6, 36.5, 88.9, 500.0}) {
    const SummitMoments n = nayak_summit_moments(alpha);
    const SummitMoments g = greenwood_summit_moments(alpha);
    EXPECT_NEAR(n.mean, g.mean, 1e-9) << alpha;
    EXPECT_NEAR(n.variance, g.variance, 1e-5) << alpha;
  }
}

TEST(Nayak, LargeAlphaTendsToGaussian) {
  const double alpha = 1e7;
  for (double x : {-2.0, -0.5, 0.0, 1.0, 2.5})
    EXPECT_NEAR(nayak_summit_pdf(x, alpha), std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi), 2e-3);
}

TEST(Nayak, SummitDensityEq367) {
  EXPECT_NEAR(nayak_summit_density(2.0, 6.0), 3.0 / (6 * std::numbers::pi * std::sqrt(3.0)), 1e-15);
}

TEST(Nayak, KsDistanceSmallForMatchingSamplesLargeOtherwise) {
  // Gaussian samples against alpha -> infinity (Gaussian): KS ~ 1/sqrt(n); shifted: large.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0, 1);
  std::vector<double> xi(20000);
  for (double& v : xi) v = g(rng);
  EXPECT_LT(ks_distance_to_nayak(xi, 1e7), 0.015);
  for (double& v : xi) v += 0.5;
  EXPECT_GT(ks_distance_to_nayak(xi, 1e7), 0.15);
}

TEST(ContactTheory, KappaValues) {
  EXPECT_NEAR(kappa_persson(), 1.5957691, 1e-7);
  EXPECT_NEAR(kappa_bgt(), 2.5066283, 1e-7);
}

TEST(ContactTheory, PerssonAreaTendsToKappaAtLowPressure) {
  const double s = 1e-5;
  EXPECT_NEAR(persson_area_fraction(s) / s, kappa_persson(), 1e-6);
  EXPECT_NEAR(persson_area_fraction(1e3), 1.0, 1e-15);
}

}  // namespace
}  // namespace wr
