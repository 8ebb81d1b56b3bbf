// Nayak's summit statistics and the analytic contact predictions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lib/analytic/area_load_fit.hpp"
#include "lib/analytic/contact_theory.hpp"
#include "lib/contact/friction_convergence.hpp"
#include "lib/contact/model_ladder.hpp"
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

namespace wr {
namespace {

// The ladder takes the cheapest model whose checks pass, and says why.
TEST(ModelLadder, AutoPicksTheCheapestValidModel) {
  ContactRequest r;
  r.load_control = true;
  r.e_star = 1.0;
  r.rms_slope = 0.1;
  r.pressure = 0.01 * r.e_star * r.rms_slope;  // sigma* = 0.01: A/A0 about 1.6 %
  EXPECT_EQ(choose_model(r).model, ContactModel::analytic);
  r.pressure = 0.3 * r.e_star * r.rms_slope;  // A/A0 about 0.32: beyond the low-pressure regime
  ModelChoice c = choose_model(r);
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.model, ContactModel::spectral);
  ASSERT_EQ(c.considered.size(), 2u);  // analytic rejected first, with its reason
  EXPECT_FALSE(all_passed(c.considered[0].second));
  r.rms_slope = 0.5;  // steep: no small-slope model; the FEM is displacement-controlled only
  r.pressure = 0.3 * r.e_star * r.rms_slope;
  EXPECT_FALSE(choose_model(r).found);
  r.load_control = false;  // --uz on the steep scene: the FEM
  EXPECT_EQ(choose_model(r).model, ContactModel::fem);
  r.rms_slope = 0.05;  // friction is never the periodic layer's (translation invariance)
  r.shear = true;
  EXPECT_EQ(choose_model(r).model, ContactModel::fem);
  EXPECT_THROW(parse_model("auto"), std::invalid_argument);
  EXPECT_EQ(parse_model("spectral"), ContactModel::spectral);
  // Friction at refine 1 is flagged (not resolved) but no other model would do better: auto
  // keeps the FEM, and the result is marked invalid.
  r.refine = 1;
  c = choose_model(r);
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.model, ContactModel::fem);
  EXPECT_FALSE(all_passed(c.considered.back().second));
  r.refine = 2;
  EXPECT_TRUE(all_passed(validity_checks(ContactModel::fem, r)));
}

// The estimated remaining change of mu (friction_convergence.hpp) on made-up histories: exact
// for geometric convergence, large for a steady creep whatever the damping, 0 when settled.
TEST(FrictionDrift, EstimatesTheChangeOfMuStillToCome) {
  const auto series = [](int n, auto f) {
    std::vector<double> v;
    for (int k = 0; k < n; ++k) v.push_back(f(k));
    return v;
  };
  const auto alpha = [&](int n, double a) { return series(n, [a](int) { return a; }); };
  EXPECT_DOUBLE_EQ(friction_drift(series(20, [](int) { return 0.2; }), alpha(20, 0.8), 0.8), 0.0);
  // Geometric approach to 0.05 (ratio 0.9 per iteration): the estimate is the true remaining change.
  const auto geometric = series(30, [](int k) { return 0.05 + 0.1 * std::pow(0.9, k); });
  EXPECT_NEAR(friction_drift(geometric, alpha(30, 0.8), 0.8) * geometric.back(), geometric.back() - 0.05, 1e-12);
  // Steady creep of 1e-3 per iteration: r = 1, capped at 0.95, i.e. 19 half-windows of 5e-3.
  const auto creep = series(30, [](int k) { return 0.2 - 1e-3 * k; });
  EXPECT_NEAR(friction_drift(creep, alpha(30, 0.8), 0.8), 19 * 5e-3 / creep.back(), 1e-9);
  // The same creep slowed 8x by a damping cut to 0.1 is just as far from settled.
  const auto slowed = series(30, [](int k) { return 0.2 - 1.25e-4 * k; });
  EXPECT_NEAR(friction_drift(slowed, alpha(30, 0.1), 0.8), 19 * 5e-3 / slowed.back(), 1e-9);
  // Short histories use shorter half-windows; two iterations are too few to say.
  EXPECT_NEAR(friction_drift({0.2, 0.19, 0.18}, alpha(3, 0.8), 0.8), 19 * 0.01 / 0.18, 1e-9);
  EXPECT_TRUE(std::isnan(friction_drift({0.2, 0.19}, alpha(2, 0.8), 0.8)));
  // A mu of about 0 (flat or symmetric scenes) is judged in absolute terms, against 1e-3.
  EXPECT_NEAR(friction_drift({1e-6, 2e-6, 2.5e-6}, alpha(3, 0.8), 0.8), 5e-7 * 0.5 / 0.5 / 1e-3, 1e-12);
}

TEST(FrictionDrift, CheckFlagsAShearStepStillSliding) {
  std::vector<ContactStep> steps(3);
  steps[0].ux = 0;  // normal load: its Fx is a by-product, never judged
  steps[0].mu_drift = 0.9;
  steps[0].converged = true;
  steps[1].ux = 1e-3;
  steps[1].mu_drift = 0.005;
  steps[1].converged = true;
  steps[2].ux = 2e-3;
  steps[2].mu_drift = 0.3;
  steps[2].converged = true;
  for (int k : {1, 2}) {  // in contact: only such a step has a mu to judge
    steps[std::size_t(k)].area_fraction = 0.1;
    steps[std::size_t(k)].fz = 1;
    steps[std::size_t(k)].mu = 0.2;
  }
  ValidityCheck c = friction_convergence_check(steps);
  EXPECT_EQ(c.name, "friction converged");
  EXPECT_FALSE(c.passed);
  EXPECT_FALSE(c.decides_model);  // a flag: no other model answers friction
  EXPECT_NE(c.detail.find("step 3"), std::string::npos) << c.detail;
  steps[2].mu_drift = 0.01;
  EXPECT_TRUE(friction_convergence_check(steps).passed);
  // A step that lost contact has no friction coefficient: its drift is not judged (issue 54).
  steps[2].mu_drift = 0.3;
  steps[2].area_fraction = 0;
  EXPECT_TRUE(friction_convergence_check(steps).passed);
  steps.resize(1);
  c = friction_convergence_check(steps);
  EXPECT_TRUE(c.passed);
  EXPECT_NE(c.detail.find("no shear step"), std::string::npos) << c.detail;
}

}  // namespace
}  // namespace wr

namespace wr {
namespace {

// The quartic of eq. 5.4 through exact quartic data: the coefficients back, R^2 = 1; through a
// YAM curve (eq. 3.179): the YAM fit recovers beta and mu for the given kappa.
TEST(AreaLoadFit, QuarticAndYamRecoverTheirParameters) {
  std::vector<double> s, a;
  for (int k = 1; k <= 10; ++k) {
    const double x = 0.05 * k;
    s.push_back(x);
    a.push_back(-0.3 * std::pow(x, 4) + 0.9 * std::pow(x, 3) - 1.2 * x * x + 2.1 * x);
  }
  const QuarticAreaFit q = fit_quartic_area(s, a);
  EXPECT_NEAR(q.kappa, 2.1, 1e-9);
  EXPECT_NEAR(q.lambda, -1.2, 1e-8);
  EXPECT_NEAR(q.omega, 0.9, 1e-7);
  EXPECT_NEAR(q.pi, -0.3, 1e-7);
  EXPECT_NEAR(q.r2, 1.0, 1e-12);
  std::vector<double> y;
  for (double x : s) y.push_back(yam_area_fraction(x, 2.3, 0.8, -1.5));
  const YamFit f = fit_yam(s, y, 2.3);
  EXPECT_NEAR(f.beta, 0.8, 1e-3);
  EXPECT_NEAR(f.mu, -1.5, 1e-3);
  EXPECT_LT(f.rms_error, 1e-6);
  // Low pressure: YAM tends to kappa sigma*.
  EXPECT_NEAR(yam_area_fraction(1e-6, 2.3, 0.8, -1.5) / (2.3e-6), 1.0, 1e-6);
  EXPECT_THROW(fit_quartic_area({0.1, 0.2}, {0.2, 0.4}), std::invalid_argument);
}

// The low-pressure kappa (sec. 5.2.3): on a curve that is linear below 15 % contact and bends
// above, the regression through the origin returns the linear slope exactly and ignores the
// bent part; least squares through the origin of a scattered line: sum(s a) / sum(s^2).
TEST(AreaLoadFit, LowPressureKappaIsTheSlopeBelowFifteenPercent) {
  std::vector<double> s, a;
  for (int k = 1; k <= 12; ++k) {
    const double x = 0.01 * k;
    s.push_back(x);
    a.push_back(x <= 0.065 ? 2.16 * x : 0.16 + 0.5 * (x - 0.065));  // flattens above 15 % contact
  }
  const LowPressureKappa k = fit_low_pressure_kappa(s, a);
  EXPECT_EQ(k.points, 6u);
  EXPECT_NEAR(k.kappa, 2.16, 1e-12);
  const LowPressureKappa scattered = fit_low_pressure_kappa({0.01, 0.02, 0.03}, {0.021, 0.039, 0.066});
  EXPECT_NEAR(scattered.kappa, (0.01 * 0.021 + 0.02 * 0.039 + 0.03 * 0.066) / (1e-4 + 4e-4 + 9e-4), 1e-12);
  EXPECT_EQ(fit_low_pressure_kappa({0.5}, {0.8}).points, 0u);  // nothing at low pressure
  EXPECT_EQ(fit_low_pressure_kappa({0.5}, {0.8}).kappa, 0.0);
  EXPECT_THROW(fit_low_pressure_kappa({0.1}, {0.2}, 0.0), std::invalid_argument);
  EXPECT_THROW(fit_low_pressure_kappa({-0.1}, {0.2}), std::invalid_argument);
}

}  // namespace
}  // namespace wr
