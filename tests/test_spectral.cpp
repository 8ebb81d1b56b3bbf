// Validation of the spectral (FFT boundary-element) contact model against exact solutions:
// Westergaard's sinusoid, Hertz's paraboloid, and the limits of the layer compliance.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lib/analytic/hertz.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "lib/spectral/surface_compliance.hpp"

namespace wr {
namespace {

constexpr double pi = std::numbers::pi;

TEST(SpectralCompliance, LayerTendsToHalfSpaceAndToUniaxialStrain) {
  ElasticBody half{2.0, 0.3};
  ElasticBody layer{2.0, 0.3, 1e-3};
  // Thick: the layer factor differs from 1 by about 4 (x^2 + x + 1) e^{-2x} / (3 - 4 nu), x = q t
  // (3.5e-3 at x = 5, 1e-13 at x = 20), always from below.
  for (double q : {3e4, 1e5}) EXPECT_NEAR(normal_compliance(layer, q) / normal_compliance(half, q), 1.0, 1e-12);
  const double r5 = normal_compliance(layer, 5e3) / normal_compliance(half, 5e3);
  EXPECT_LT(r5, 1.0);
  EXPECT_NEAR(r5, 1.0 - 4 * 31 * std::exp(-10.0) / (3 - 4 * 0.3), 5e-4);
  // Thin: uniaxial strain, t / M, and continuity of the small-x series.
  const double uniaxial = layer.thickness / layer.p_wave_modulus();
  EXPECT_NEAR(normal_compliance(layer, 0.0) / uniaxial, 1.0, 1e-15);
  EXPECT_NEAR(normal_compliance(layer, 1.0) / uniaxial, 1.0, 1e-5);
  EXPECT_NEAR(normal_compliance(layer, 0.0999) / normal_compliance(layer, 0.1001), 1.0, 1e-5);
  EXPECT_NEAR(normal_compliance(layer, 19999.0) / normal_compliance(layer, 20001.0), 20001.0 / 19999.0, 1e-9);
  EXPECT_TRUE(std::isinf(normal_compliance(half, 0.0)));
  EXPECT_THROW(check_body(ElasticBody{1.0, 0.5}), std::invalid_argument);
}

// A wavy surface h = D cos(2 pi x / lambda) (one row, the plane-strain problem) pressed by a
// mean pressure pm < p* = pi E* D / lambda (Johnson, Contact Mechanics, sec. 13.2):
//   p(x) = (2 pm / s_a) cos(pi x / lambda) sqrt(s_a - sin^2(pi x / lambda)),  s_a = sin^2(pi a / lambda) = pm / p*.
// So p^2 / cos^2 is linear in sin^2: a line fit through the contact points gives s_a, hence
// the contact width 2a, without the one-sample granularity of counting contact points.
struct WaveFit {
  double s_a = 0, scale = 0;
};
WaveFit fit_westergaard(const std::vector<double>& p, double dx, double lambda) {
  double s1 = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  double s_max = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p[k] > 0) s_max = std::max(s_max, std::pow(std::sin(pi * double(k) * dx / lambda), 2));
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double s = std::pow(std::sin(pi * double(k) * dx / lambda), 2);
    if (!(p[k] > 0) || s > 0.8 * s_max) continue;  // away from the edge, where sampling cuts the root
    const double y = p[k] * p[k] / (1 - s);
    s1 += s;
    sy += y;
    sxx += s * s;
    sxy += s * y;
    ++n;
  }
  const double slope = (n * sxy - s1 * sy) / (n * sxx - s1 * s1), icpt = (sy - slope * s1) / n;
  return {icpt / -slope, -slope};
}

TEST(SpectralNormal, SinusoidMatchesWestergaard) {
  const std::size_t n = 4096;
  const double lambda = 1e-3, D = 1e-5, E = 1.0, nu = 0.45;
  HeightMap wave(n, 1, lambda / double(n), lambda / double(n));
  for (std::size_t k = 0; k < n; ++k) wave.h[k] = D * std::cos(2 * pi * double(k) / double(n));
  const ElasticBody body{E, nu};
  SpectralNormalContact solver(wave, body, 1);
  const double p_star = pi * body.e_star() * D / lambda;
  SpectralOptions opt;
  opt.tolerance = 1e-12;
  for (double ratio : {0.05, 0.2, 0.5, 0.8}) {
    const SpectralNormalResult r = solver.solve_load(ratio * p_star, opt);
    ASSERT_TRUE(r.converged) << r.message;
    const WaveFit f = fit_westergaard(solver.pressure(), wave.dx, lambda);
    const double width = 2 * std::asin(std::sqrt(f.s_a)) / pi;           // 2a / lambda, fitted
    const double exact = 2 * std::asin(std::sqrt(ratio)) / pi;           // Westergaard
    EXPECT_NEAR(width / exact, 1.0, 1e-3) << "pm/p* = " << ratio;
    EXPECT_NEAR(std::sqrt(f.scale) * ratio / (2 * ratio * p_star), 1.0, 1e-3) << "pressure scale, pm/p* = " << ratio;
    // The counted contact fraction agrees to within the two edge samples.
    EXPECT_NEAR(r.area_fraction, exact, 2.0 / double(n) + 1e-12);
  }
  // Full contact: p = pm + p* cos(2 pi x / lambda), everywhere.
  const double pm = 1.5 * p_star;
  const SpectralNormalResult r = solver.solve_load(pm, opt);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.area_fraction, 1.0);
  double worst = 0;
  for (std::size_t k = 0; k < n; ++k)
    worst = std::max(worst, std::abs(solver.pressure()[k] - (pm + p_star * std::cos(2 * pi * double(k) / double(n)))));
  EXPECT_LT(worst / p_star, 1e-3);
}

// A paraboloid in a period 16 x its contact radius: Hertz's radius and force within 1 %.
TEST(SpectralNormal, ParaboloidMatchesHertz) {
  const std::size_t n = 512;
  const double L = 1e-2, R = 5e-2, nu = 0.45, a_target = L / 16;
  const ElasticBody body{1.0, nu};
  const double F = hertz_force(a_target, R, body.e_star());
  SpectralNormalContact solver(paraboloid_cap(n, L, R), body, 1);
  SpectralOptions opt;
  opt.tolerance = 1e-10;
  const SpectralNormalResult r = solver.solve_load(F / (L * L), opt);
  ASSERT_TRUE(r.converged) << r.message;
  const double h = L / double(n);
  const HertzFit fit = fit_hertz_pressure(solver.pressure(), int(n), int(n), h, L / 2, L / 2, a_target);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.radius / a_target, 1.0, 0.01);
  EXPECT_NEAR(hertz_force(fit.radius, R, body.e_star()) / F, 1.0, 0.01);
  EXPECT_NEAR(fit.peak_pressure / (3 * F / (2 * pi * a_target * a_target)), 1.0, 0.01);
  EXPECT_LT(r.max_penetration, 1e-6 * a_target * a_target / R);
}

// Displacement control on a layer agrees with load control at the load it produces.
TEST(SpectralNormal, DisplacementAndLoadControlAgreeOnALayer) {
  const std::size_t n = 128;
  const double L = 1e-2, R = 5e-2;
  const ElasticBody body{1.0, 0.45, L};
  SpectralNormalContact a(paraboloid_cap(n, L, R), body, 1), b(paraboloid_cap(n, L, R), body, 1);
  SpectralOptions opt;
  opt.tolerance = 1e-12;
  const SpectralNormalResult ra = a.solve_approach(2e-4, opt);
  ASSERT_TRUE(ra.converged) << ra.message;
  const SpectralNormalResult rb = b.solve_load(ra.mean_pressure, opt);
  ASSERT_TRUE(rb.converged) << rb.message;
  EXPECT_NEAR(rb.approach / 2e-4, 1.0, 1e-8);
  EXPECT_NEAR(rb.area_fraction, ra.area_fraction, 1e-12);
  EXPECT_THROW(SpectralNormalContact(paraboloid_cap(n, L, R), ElasticBody{1.0, 0.45}, 1).solve_approach(1e-4, opt),
               std::invalid_argument);
}

}  // namespace
}  // namespace wr
