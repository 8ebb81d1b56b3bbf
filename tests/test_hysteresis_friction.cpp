// Persson's hysteresis friction (lib/friction/hysteresis_friction.hpp) against exact answers:
// the angle integrals against a brute-force quadrature, a single Maxwell element on a one-band
// surface against its closed-form inner integrals (derivation in docs/friction-model.md), the
// limits v -> 0 and v -> infinity, the scaling of E and sigma0, the flash temperature's isothermal
// limit, the q-quadrature's convergence, and the causality check of a modulus table.
#include <gtest/gtest.h>

#include "tests/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "lib/core/errors.hpp"
#include "lib/friction/compound.hpp"
#include "lib/friction/flash_temperature.hpp"
#include "lib/friction/hysteresis_friction.hpp"
#include "lib/friction/modulus_table.hpp"
#include "lib/friction/friction_scene.hpp"
#include "roads/psd_fit.hpp"
#include "roads/self_affine_psd.hpp"
#include "roads/spectrum.hpp"
#include "roads/synthesize.hpp"
#include "water/rain_fill.hpp"

namespace wr {
namespace {

Compound maxwell(double er, double de, double tau) {
  Compound c;
  c.name = "one Maxwell element";
  c.source = "test";
  c.synthetic = true;
  c.poisson = 0.5;
  c.e_relaxed = er;
  c.terms = {{tau, de}};
  c.thermal = ThermalProperties{1200, 1500, 0.25};
  return c;
}

// A tread-like compound: loss spread over eight decades (rubbery 5 MPa, glassy ~1.6 GPa).
Compound broad_compound() {
  Compound c = maxwell(5e6, 0, 1);
  c.terms.clear();
  for (int i = 0; i <= 24; ++i) {
    const double lt = -11 + i / 3.0;  // log10 tau from -11 to -3
    c.terms.push_back({std::pow(10.0, lt), 2e8 * std::exp(-0.5 * std::pow((lt + 7) / 1.5, 2))});
  }
  return c;
}

using wr_test::gauss_legendre;

// int_0^{pi/2} f(cos phi) dphi by brute force: phi in [0, pi/3] directly, and u = cos phi in
// [1e-17, 1/2] in ln u (du / sqrt(1 - u^2)), which resolves the features at u ~ 1/(omega tau).
double quarter_angle_integral(const std::function<double(double)>& f) {
  const double near = gauss_legendre([&](double p) { return f(std::cos(p)); }, 0, M_PI / 3, 200);
  const double far = gauss_legendre(
      [&](double y) {
        const double u = std::exp(y);
        return f(u) * u / std::sqrt(1 - u * u);
      },
      std::log(1e-17), std::log(0.5), 4000);
  return near + far;
}

TEST(HysteresisFriction, AngleIntegralsMatchBruteForceQuadrature) {
  const Compound c = broad_compound();
  for (double omega : {1e-2, 1.0, 1e4, 1e7, 1e10, 1e13}) {
    const AngleIntegrals a = angle_integrals(c, omega, 1.0);
    const double loss = 4 * quarter_angle_integral([&](double u) { return u * c.modulus_at_reference(omega * u).imag(); });
    const double power = 4 * quarter_angle_integral([&](double u) { return std::norm(c.modulus_at_reference(omega * u)); });
    EXPECT_NEAR(a.loss, loss, 1e-9 * std::abs(loss) + 1e-6) << omega;
    EXPECT_NEAR(a.power, power, 1e-9 * power) << omega;
  }
}

// One Maxwell element (Er, dE, tau) on C = c for qa <= q <= qb: with b = v tau, x = b^2 q^2 and
// s = sqrt(1 + x), the angle integrals are 2 pi dE (1 - 1/s) / (b q) and
// 2 pi (Eg^2 - (Eg^2 - Er^2) / s), so
//   G(q) = pi c / (4 E0^2) [Eg^2 (q^4 - qa^4) / 4 - (Eg^2 - Er^2) (K(q) - K(qa))],
//   K(q) = int_0^q q'^3 / s dq' = q^4 (s + 2) / (3 (s + 1)^2)   (= (s^3 - 3 s + 2) / (3 b^4)),
//   mu = pi c dE / E0 int_qa^qb q^3 P(q) (1 - 1/s) / (b q) dq,  (1 - 1/s) = x / (s (1 + s)),
//   P = erf(1 / (2 sqrt G)).
// Every piece is written without cancellation at small b q. The last integral (erf of a closed
// form) is done by 20-point Gauss-Legendre on 400 panels.
double maxwell_band_mu(double er, double de, double tau, double qa, double qb, double c, double v, double e0) {
  const double eg = er + de, b = v * tau;
  auto K = [&](double q) {
    const double s = std::sqrt(1 + b * b * q * q);
    return std::pow(q, 4) * (s + 2) / (3 * (s + 1) * (s + 1));
  };
  auto G = [&](double q) {
    return M_PI * c / (4 * e0 * e0) * (eg * eg * (std::pow(q, 4) - std::pow(qa, 4)) / 4 - (eg * eg - er * er) * (K(q) - K(qa)));
  };
  auto integrand = [&](double q) {
    const double g = G(q), s = std::sqrt(1 + b * b * q * q);
    const double p = g > 0 ? std::erf(1 / (2 * std::sqrt(g))) : 1.0;
    return q * q * p * b * q * q / (s * (1 + s));
  };
  return M_PI * c * de / e0 * gauss_legendre(integrand, qa, qb, 400);
}

TEST(HysteresisFriction, SingleMaxwellElementOnOneBandMatchesClosedForm) {
  const double er = 3e6, de = 3e8, tau = 1e-5, qa = 1e3, qb = 1e4, pressure = 2e5;
  const Compound comp = maxwell(er, de, tau);
  const double e0 = 0.75 * pressure;
  // c chosen so that h0 = 0.1 mm: h0^2 = 2 pi c (qb^2 - qa^2) / 2.
  const double c = 1e-8 / (M_PI * (qb * qb - qa * qa));
  const RoughnessSpectrum psd = band_spectrum(qa, qb, c);
  FrictionOptions opt;
  opt.pressure = pressure;
  opt.temperature = comp.reference_temperature;
  opt.points_per_decade = 4000;
  for (double v : {1e-3, 1e-2, 0.1, 1.0, 10.0}) {
    const double exact = maxwell_band_mu(er, de, tau, qa, qb, c, v, e0);
    const FrictionPoint p = hysteresis_friction(psd, comp, v, opt);
    EXPECT_NEAR(p.mu, exact, 1e-6 * exact) << "v = " << v;
    EXPECT_GT(exact, 1e-4);
  }
}

RoughnessSpectrum road_like_spectrum() {
  // Self-affine (H = 0.8) from qL = 2 pi / 0.1 m through q0 = 6 qL to q1 = 1e6 1/m, h0 = 0.3 mm.
  const SelfAffinePsd law = SelfAffinePsd::from_eq44(3e-4, 0.8, 2 * M_PI / 0.1, 12 * M_PI / 0.1, 1e6);
  RoughnessSpectrum s;
  for (double lq = std::log10(law.qL); lq <= 6 + 1e-9; lq += 0.05) {
    s.q.push_back(std::pow(10.0, lq));
    s.C.push_back(law(std::pow(10.0, lq)));
  }
  s.q_start = s.q.front();
  s.q_end = s.q.back();
  s.q_measured = s.q_end;
  return s;
}

TEST(HysteresisFriction, VanishesAtZeroAndInfiniteSpeed) {
  const Compound comp = broad_compound();
  const RoughnessSpectrum psd = road_like_spectrum();
  FrictionOptions opt;
  const double peak = hysteresis_friction(psd, comp, 1e-2, opt).mu;
  EXPECT_GT(peak, 0.1);
  // Excitation frequencies q v far below the slowest relaxation (tau 1e-3 s) or far above the fastest (1e-11 s).
  EXPECT_LT(hysteresis_friction(psd, comp, 1e-14, opt).mu, 1e-3 * peak);
  EXPECT_LT(hysteresis_friction(psd, comp, 1e13, opt).mu, 1e-3 * peak);
}

TEST(HysteresisFriction, ScalingModulusAndPressureTogetherLeavesMuUnchanged) {
  Compound comp = broad_compound();
  const RoughnessSpectrum psd = road_like_spectrum();
  FrictionOptions opt;
  const double mu = hysteresis_friction(psd, comp, 0.1, opt).mu;
  comp.e_relaxed *= 7;
  for (PronyTerm& t : comp.terms) t.de *= 7;
  opt.pressure *= 7;
  EXPECT_NEAR(hysteresis_friction(psd, comp, 0.1, opt).mu, mu, 1e-10 * mu);
}

TEST(HysteresisFriction, QuadratureConvergesInTheNodeCount) {
  const Compound comp = broad_compound();
  const RoughnessSpectrum psd = road_like_spectrum();
  FrictionOptions fine, normal;
  fine.points_per_decade = 400;
  for (double v : {1e-4, 1e-2, 1.0, 17.9}) {
    const double ref = hysteresis_friction(psd, comp, v, fine).mu;
    EXPECT_NEAR(hysteresis_friction(psd, comp, v, normal).mu, ref, 1e-4 * ref) << v;
  }
}

// A 128^2 self-affine map (25.6 mm, h0 0.3 mm, H 0.7).
HeightMap small_map(std::uint64_t seed) {
  SynthParams p;
  p.nx = p.ny = 128;
  p.dx = 2e-4;
  p.seed = seed;
  return synthesize(p).map;
}

// The same on the spectrum of a synthesized map (log-averaged nodes, extension to q1) with the
// flash temperature: the fixed point and the quadrature together.
TEST(HysteresisFriction, MapSpectrumWithFlashTemperatureConverges) {
  const HeightMap map = small_map(5);
  FrictionScene s;
  s.compound = broad_compound();
  s.options.flash_temperature = true;
  s.speeds = {1e-3, 0.1, 17.9};
  FrictionScene fine = s;
  fine.options.points_per_decade = 400;
  const FrictionRun a = run_friction(map, std::nullopt, s, "map"), b = run_friction(map, std::nullopt, fine, "map");
  ASSERT_TRUE(a.dry_spectrum.extrapolated());
  for (std::size_t i = 0; i < s.speeds.size(); ++i)
    EXPECT_NEAR(a.dry.points[i].mu, b.dry.points[i].mu, 1e-4 * b.dry.points[i].mu) << s.speeds[i];
}

// Sealing: a "wet" surface without water is the dry one for both models; at the drained limit
// both lie below the dry curve at every speed, the local model below the homogeneous one.
TEST(Sealing, NoWaterIsDryAndPoolsLowerFriction) {
  const HeightMap map = small_map(6);
  FrictionScene s;
  s.compound = broad_compound();
  s.speeds = {1e-4, 1e-2, 1.0, 17.9};
  const FrictionRun same = run_friction(map, WetSurface{&map, 0.0}, s, "map");
  for (std::size_t i = 0; i < s.speeds.size(); ++i) {
    EXPECT_NEAR(same.wet_homogeneous->points[i].mu, same.dry.points[i].mu, 1e-12 * same.dry.points[i].mu);
    EXPECT_NEAR(same.wet_local->points[i].mu, same.dry.points[i].mu, 1e-12 * same.dry.points[i].mu);
  }
  FillRequest req;
  req.limit = true;
  const FillResult f = fill_water(map, req);
  HeightMap wet = map;
  std::copy(f.water.level.begin(), f.water.level.end(), wet.h.begin());
  ASSERT_GT(f.water.coverage, 0.3);
  const FrictionRun r = run_friction(map, WetSurface{&wet, f.water.coverage}, s, "map");
  for (std::size_t i = 0; i < s.speeds.size(); ++i) {
    EXPECT_LT(r.wet_homogeneous->points[i].mu, r.dry.points[i].mu) << s.speeds[i];
    EXPECT_LT(r.wet_local->points[i].mu, r.wet_homogeneous->points[i].mu) << s.speeds[i];
    EXPECT_GT(r.wet_local->points[i].mu, 0);
  }
}

TEST(HysteresisFriction, FlashTemperatureWithInstantHeatRemovalIsTheIsothermalTheory) {
  Compound comp = broad_compound();
  const RoughnessSpectrum psd = road_like_spectrum();
  FrictionOptions off, on;
  on.flash_temperature = true;
  const double iso = hysteresis_friction(psd, comp, 1.0, off).mu;
  comp.thermal->conductivity = 1e12;  // heat leaves the contact at once: no rise
  const FrictionPoint p = hysteresis_friction(psd, comp, 1.0, on);
  EXPECT_LT(p.temperature_rise, 1e-6);
  EXPECT_NEAR(p.mu, iso, 1e-6 * iso);
  // With tread rubber's conductivity, 1 m/s heats the contact and lowers mu on the glassy side.
  comp.thermal->conductivity = 0.25;
  const FrictionPoint hot = hysteresis_friction(psd, comp, 1.0, on);
  EXPECT_GT(hot.temperature_rise, 1.0);
  EXPECT_NE(hot.mu, iso);
}

TEST(FlashTemperature, KernelMatchesItsIntegralAndLimits) {
  const double D = 0.25 / (1200 * 1500.0);
  for (double q : {1e3, 1e5, 1e7})
    for (double v : {1e-4, 1e-2, 1.0, 30.0}) {
      const double b = q, kappa = 2 * q / M_PI, t = M_PI / (q * v);
      // The k integral in k = b tan(x) (x in [0, pi/2)): 2b dk / (k^2 + b^2) = 2 dx.
      const double direct = gauss_legendre(
          [&](double x) {
            const double k = b * std::tan(x), m = D * (k * k + kappa * kappa);
            return 2 / M_PI * -std::expm1(-m * t) / m;
          },
          0, M_PI / 2, 2000);
      EXPECT_NEAR(flash_kernel(b, kappa, D, t), direct, 1e-7 * direct) << q << " " << v;
    }
  // Adiabatic (short) and steady (long) limits.
  EXPECT_NEAR(flash_kernel(1e3, 2e3 / M_PI, D, 1e-9), 1e-9, 1e-12);
  EXPECT_NEAR(flash_kernel(1e3, 2e3 / M_PI, D, 1e9), 1 / (D * (2e3 / M_PI) * (1e3 + 2e3 / M_PI)), 1e-6 / (D * 1e6));
  for (double x : {0.0, 0.5, 3.0, 4.999, 5.0, 20.0})
    EXPECT_NEAR(erfcx(x), std::exp(x * x) * std::erfc(x), 2e-9 * erfcx(x)) << x;  // erfc(20) ~ 5e-176 is still a normal double
}

ModulusTable table_of(const Compound& c) {
  ModulusTable t;
  for (double lw = -2; lw <= 12 + 1e-9; lw += 0.25) {
    const std::complex<double> e = c.modulus_at_reference(std::pow(10.0, lw));
    t.omega.push_back(std::pow(10.0, lw));
    t.storage.push_back(e.real());
    t.loss.push_back(e.imag());
  }
  return t;
}

TEST(ModulusTable, PronyCompoundPassesTheCausalityCheckAndKeepsItsFriction) {
  const Compound comp = broad_compound();
  const PronyFit fit = causal_prony_fit(table_of(comp), "table.json");
  EXPECT_LT(fit.max_misfit, 0.01);
  Compound refit = comp;
  refit.e_relaxed = fit.e_relaxed;
  refit.terms = fit.terms;
  const RoughnessSpectrum psd = road_like_spectrum();
  FrictionOptions opt;
  const double mu = hysteresis_friction(psd, comp, 0.01, opt).mu;
  EXPECT_NEAR(hysteresis_friction(psd, refit, 0.01, opt).mu, mu, 0.01 * mu);
}

TEST(ModulusTable, CorruptedTablesFailTheCausalityCheck) {
  const Compound comp = broad_compound();
  // Loss tripled over two decades while the storage modulus is left as it was.
  ModulusTable loss_boost = table_of(comp);
  for (std::size_t i = 0; i < loss_boost.omega.size(); ++i)
    if (loss_boost.omega[i] > 1e5 && loss_boost.omega[i] < 1e7) loss_boost.loss[i] *= 3;
  EXPECT_THROW(causal_prony_fit(loss_boost, "boost.json"), InputError);
  // A storage modulus that falls with frequency: no relaxing material does that.
  ModulusTable falling = table_of(comp);
  std::reverse(falling.storage.begin(), falling.storage.end());
  try {
    causal_prony_fit(falling, "falling.json");
    FAIL() << "a falling storage modulus passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("falling.json: table: not causal"), std::string::npos) << e.what();
  }
}

TEST(HysteresisFriction, BadOptionsAreRefusedByName) {
  const Compound comp = broad_compound();
  FrictionOptions opt;
  opt.pressure = 0;
  EXPECT_THROW(check_friction_options(opt, comp), InputError);
  opt.pressure = 1e5;
  EXPECT_THROW(hysteresis_friction(road_like_spectrum(), comp, 0.0, opt), InputError);
  EXPECT_THROW(hysteresis_friction(road_like_spectrum(), comp, -1.0, opt), InputError);
}

}  // namespace
}  // namespace wr

namespace wr {
namespace {

// The rms-slope criterion of the cut-off (issue 56): the spectrum cut at the q1 it picks has
// exactly the asked rms slope, sqrt(2 pi int q^3 C dq) by an independent quadrature (Simpson in ln q
// between the spectrum's nodes), and q1 grows with the slope asked.
TEST(CutOffCriterion, RmsSlopeCriterionGivesTheAskedSlope) {
  SynthParams p;
  p.nx = p.ny = 128;
  p.dx = 1e-4;
  p.h0 = 1e-4;
  p.hurst = 0.7;
  p.q0_ratio = 4;
  p.seed = 5;
  const HeightMap map = synthesize(p).map;
  const SpectrumResult sp = analyze_spectrum(map);
  const PsdFit fit = fit_self_affine(sp.psd, sp.nyquist, false);
  double last = 0;
  for (double slope : {0.8, 1.3, 2.0}) {
    const double q1 = q1_for_rms_slope(sp.psd, sp.nyquist, fit, slope, "map", "--q1");
    EXPECT_GT(q1, last);
    last = q1;
    const RoughnessSpectrum c = spectrum_from_psd(sp.psd, sp.nyquist, fit, q1, "map");
    const double a = std::log(c.q_start), b = std::log(c.q_end);
    const int n = 20000;
    double s = 0;
    for (int k = 0; k <= n; ++k) {
      const double q = std::exp(a + (b - a) * k / n), f = 2 * M_PI * std::pow(q, 4) * c(q);
      s += f * (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2));
    }
    s *= (b - a) / n / 3;
    EXPECT_NEAR(std::sqrt(s) / slope, 1.0, 1e-3) << slope;
  }
  EXPECT_THROW(q1_for_rms_slope(sp.psd, sp.nyquist, fit, 0, "map", "--q1"), InputError);
}

}  // namespace
}  // namespace wr
