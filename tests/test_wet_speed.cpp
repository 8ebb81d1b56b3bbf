// Wet friction at speed (issue 55): the effective-medium conductance, Persson's load-separation,
// the squeeze-out of a film (lib/friction/squeeze_out.hpp) against Reynolds' closed form and an
// independent ODE integration, the speed constant's fit, the tyre tests, and the command line's
// answers to bad input.
#include <gtest/gtest.h>

#include "tests/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "lib/core/errors.hpp"
#include "lib/flow/effective_medium.hpp"
#include "lib/friction/load_separation.hpp"
#include "lib/friction/skid_at_speed.hpp"
#include "lib/friction/squeeze_out.hpp"
#include "lib/friction/tyre_test.hpp"
#include "tests/cli_fixture.hpp"

namespace wr {
namespace {

// --- effective medium -------------------------------------------------------------------------

TEST(EffectiveMedium, ParallelPlatesAndBinaryMediumAreExact) {
  // No spread, no contact: parallel plates at the mean gap.
  EXPECT_NEAR(effective_medium_conductance({0, 20e-6, 0}) / (std::pow(20e-6, 3) / 12), 1.0, 1e-12);
  // A binary medium (contact fraction A, free gap g = u/(1-A)): Bruggeman's equation with the
  // threshold A_c solves to K = g^3/12 (1 - A / A_c) (derivation in the header's terms).
  for (double ac : {0.42, 0.5})
    for (double A : {0.05, 0.2, 0.35}) {
      const double u = 10e-6, g = u / (1 - A);
      const double exact = g * g * g / 12 * (1 - A / ac);
      EXPECT_NEAR(effective_medium_conductance({A, u, 0}, ac) / exact, 1.0, 1e-10) << "A " << A << " A_c " << ac;
    }
  // At and beyond the threshold the free area does not percolate: exactly zero.
  EXPECT_EQ(effective_medium_conductance({0.42, 1e-5, 1e-5}), 0.0);
  EXPECT_EQ(effective_medium_conductance({0.6, 1e-5, 1e-5}, 0.5), 0.0);
  EXPECT_THROW(effective_medium_conductance({-0.1, 1e-5, 0}), std::invalid_argument);
}

TEST(EffectiveMedium, SpreadLowersTheConductanceBelowTheArithmeticMean) {
  // A 2-D medium lies between the harmonic and the arithmetic mean of its conductances; with
  // a folded normal of rms h the arithmetic mean of u^3/12 is known in closed form at m >> h:
  // <u^3> = m^3 + 3 m h^2.
  const double m = 50e-6, h = 5e-6;
  const double K = effective_medium_conductance({0, m, h});
  const double arithmetic = (m * m * m + 3 * m * h * h) / 12;
  EXPECT_LT(K, arithmetic);
  EXPECT_GT(K, m * m * m / 12 * 0.95);
  // and it falls monotonically as contact spreads at the same free gaps
  double last = K;
  for (double A : {0.1, 0.2, 0.3, 0.4}) {
    const double k = effective_medium_conductance({A, m * (1 - A), h});
    EXPECT_LT(k, last);
    last = k;
  }
}

// --- load-separation ----------------------------------------------------------------------------

Compound elastic_rubber(double e) {
  Compound c;
  c.name = "elastic";
  c.poisson = 0.5;
  c.e_relaxed = e;
  return c;  // no Prony terms: E(omega) = e at every frequency
}

TEST(LoadSeparation, KernelMatchesDirectQuadrature) {
  for (double x0 : {1e-6, 1e-2, 0.3, 1.0, 2.5}) {
    // Simpson's rule in ln x on [x0, 8], 200000 intervals.
    const double g = kLoadSeparationGamma, a = std::log(x0), b = std::log(8.0);
    const int n = 200000;
    const double h = (b - a) / n;
    double s = 0;
    for (int i = 0; i <= n; ++i) {
      const double x = std::exp(a + i * h), e = std::erf(x);
      const double f = (g + 3 * (1 - g) * e * e) * std::exp(-x * x);
      s += f * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
    }
    s *= h / 3;
    EXPECT_NEAR(load_separation_kernel(x0, g), s, 1e-8 * s) << "x0 " << x0;
  }
}

TEST(LoadSeparation, ElasticContactAreaIsPerssonsErf) {
  // One band C = c on [qa, qb]: int q^3 C dq = c (qb^4 - qa^4) / 4, so A/A0 = erf(p w(q1) / E*)
  // with w(q1) = (pi c (qb^4 - qa^4) / 4)^(-1/2) (Persson's contact area, the same P(q1) as the
  // hysteresis model's at this speed).
  const double qa = 1e3, qb = 1e5, c = 1e-22, e = 10e6, estar = e / 0.75;
  const RoughnessSpectrum psd = band_spectrum(qa, qb, c);
  const LoadSeparation ls(psd, elastic_rubber(e), 1.0, 20, 200);
  const double w1 = 1 / std::sqrt(M_PI * c * (std::pow(qb, 4) - std::pow(qa, 4)) / 4);
  for (double p : {1e4, 1e5, 1e6}) EXPECT_NEAR(ls.contact_fraction(p), std::erf(p * w1 / estar), 2e-4) << p;
  // rms height: h0^2 = 2 pi c (qb^2 - qa^2) / 2
  EXPECT_NEAR(ls.rms_height() / std::sqrt(M_PI * c * (qb * qb - qa * qa)), 1.0, 1e-3);
  // u(p) decreases; pressure_at inverts it
  double last = INFINITY;
  for (double p : {1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
    const double u = ls.separation(p);
    EXPECT_LT(u, last);
    last = u;
    if (u > 0) {  // u = 0: full contact
      EXPECT_NEAR(ls.pressure_at(u) / p, 1.0, 1e-8) << "p " << p << " u " << u;
    }
  }
  // Separated surfaces: u(p) = u* - gamma sqrt(pi) (int q^2 C w dq) ln p + ..., the exponential
  // law; its slope in ln p, at two small pressures, is the same to 1e-3.
  const double s1 = ls.separation(1e-3) - ls.separation(1e-2), s2 = ls.separation(1e-2) - ls.separation(1e-1);
  EXPECT_NEAR(s1 / s2, 1.0, 1e-3);
}

using wr_test::gauss_legendre;

// --- squeeze-out --------------------------------------------------------------------------------

SqueezeLaw smooth_plates() {
  SqueezeLaw law;
  law.separation = [](double) { return 0.0; };
  law.contact = [](double) { return 0.0; };
  // the effective medium without roughness or contact: parallel plates
  law.conductance = [](double u, double A) { return effective_medium_conductance({A, u, 0}); };
  return law;
}

TEST(SqueezeOut, SmoothPlatesFollowReynoldsClosedForm) {
  SqueezeSetup s;
  s.pressure = 0.3e6;
  s.viscosity = 1e-3;
  s.drainage_length = 0.018;
  s.initial_separation = 0.5e-3;
  const SqueezeHistory h(smooth_plates(), s);
  for (const SqueezeState& st : h.nodes()) {
    if (st.t <= 0) continue;
    const double exact = smooth_plates_squeeze_time(1e-3, 0.018, 0.3e6, 0.5e-3, st.separation);
    ASSERT_NEAR(st.t / exact, 1.0, 1e-3) << "u " << st.separation;  // the bar asks 1 %
  }
  // t ~ eta L^2 / (sigma0 u^2): u at t is the closed form's inverse
  const double t = 0.01, u = 1 / std::sqrt(2 * 0.3e6 * t / (1e-3 * 0.018 * 0.018) + 1 / (0.5e-3 * 0.5e-3));
  EXPECT_NEAR(h.at(t).separation / u, 1.0, 1e-3);
  EXPECT_EQ(h.mean_load_share(1.0), 0.0);  // no asperities: the water carries everything
}

TEST(SqueezeOut, RoughInterfaceMatchesAnIndependentOdeIntegration) {
  // Asperities with the exponential law p_c = P exp(-u / U), contact A = p_c / (2 sigma0), and
  // the effective-medium conductance; the reference integrates du/dt = -12 K (sigma0 - p_c) /
  // (eta L^2) with classical RK4 in t.
  const double P = 30e6, U = 20e-6, sigma0 = 0.3e6, eta = 1e-3, L = 0.02, rms = 8e-6;
  SqueezeLaw law;
  law.separation = [=](double p) { return U * std::log(P / p); };
  law.contact = [=](double p) { return 0.5 * p / sigma0 * 0.2; };
  law.conductance = [=](double u, double A) { return effective_medium_conductance({A, u, rms}); };
  SqueezeSetup s{sigma0, eta, L, 0.4e-3};
  const SqueezeHistory h(law, s);
  // Reference: t(u) = int_u^u0 du' / |du/dt| by 20-point Gauss-Legendre on 400 panels in u
  // (the implementation integrates in ln u and ln p_c, with the trapezoid rule).
  auto inverse_rate = [&](double u) {
    const double p = P * std::exp(-u / U), A = law.contact(std::min(p, sigma0));
    return eta * L * L / (12 * law.conductance(u, A) * (sigma0 - p));
  };
  const double u_eq = U * std::log(P / sigma0);
  for (double share : {0.01, 0.3, 0.9}) {
    const double u = U * std::log(P / (share * sigma0));
    const double t = gauss_legendre(inverse_rate, u, s.initial_separation, 400);
    EXPECT_NEAR(h.at(t).separation / u, 1.0, 2e-3) << "share " << share;
    EXPECT_NEAR(h.time_to_share(share) / t, 1.0, 1e-2) << "share " << share;
  }
  EXPECT_GT(u_eq, 0);
  EXPECT_NEAR(h.at(10.0).asperity_pressure / sigma0, 1.0, 1e-3);  // equilibrium: asperities carry all
  EXPECT_GT(h.time_to_share(0.9), h.time_to_share(0.01));
}

TEST(SqueezeOut, NonPercolatingInterfaceTrapsTheWater) {
  // Contact beyond the effective medium's threshold before equilibrium: the flow stops.
  SqueezeLaw law;
  law.separation = [](double p) { return 20e-6 * std::log(30e6 / p); };
  law.contact = [](double p) { return std::min(0.9, p / 0.3e6); };
  law.conductance = [](double u, double A) { return effective_medium_conductance({A, u, 5e-6}); };
  const SqueezeHistory h(law, {0.3e6, 1e-3, 0.02, 0.3e-3});
  EXPECT_TRUE(h.trapped());
  EXPECT_LT(h.nodes().back().asperity_pressure, 0.43 * 0.3e6);
}

// --- speed constant, tyre tests -----------------------------------------------------------------

TEST(SkidNumbers, SpeedConstantOfAnExactExponential) {
  std::vector<double> s, mu;
  for (int v = 20; v <= 100; v += 5) s.push_back(v), mu.push_back(0.55 * std::exp((20.0 - v) / 47.0));
  const auto [sp, rms] = fit_speed_constant(s, mu);
  EXPECT_NEAR(sp, 47.0, 1e-9);
  EXPECT_NEAR(rms, 0.0, 1e-12);
  const auto flat = fit_speed_constant({20, 60, 100}, {0.5, 0.5, 0.51});
  EXPECT_TRUE(std::isinf(flat.first));
}

TEST(SkidNumbers, WaterViscosityFollowsIapws) {
  EXPECT_NEAR(water_viscosity(0) / 1.792e-3, 1.0, 0.025);
  EXPECT_NEAR(water_viscosity(20) / 1.002e-3, 1.0, 0.01);
  EXPECT_NEAR(water_viscosity(50) / 0.547e-3, 1.0, 0.025);
  EXPECT_NEAR(water_viscosity(100) / 0.282e-3, 1.0, 0.025);
}

TEST(SkidNumbers, BuiltInTestsAndFilesWithTheirErrors) {
  EXPECT_NEAR(tyre_test("e274-ribbed").drainage_length, 0.018, 0);
  EXPECT_NEAR(tyre_test("e274-smooth").drainage_length, 0.15, 0);
  EXPECT_NEAR(tyre_test("e274-smooth").water_film, 0.5e-3, 0);
  const std::string dir = ::testing::TempDir();
  auto file = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + name) << text;
    return dir + name;
  };
  const std::string good = file("t1.json", R"({"name":"mine","patch_length_m":0.1,"drainage_length_m":0.01,"slip_speed_m_s":10})");
  const TyreTest t = tyre_test(good);
  EXPECT_EQ(t.name, "mine");
  EXPECT_EQ(t.drainage_length, 0.01);
  EXPECT_EQ(t.water_film, 0.5e-3);
  auto message = [&](const std::string& path) {
    try {
      tyre_test(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(file("t2.json", R"({"name":"x","patch_length_m":0.1,"slip_speed_m_s":10})")).find("drainage_length_m"), std::string::npos);
  EXPECT_NE(message(file("t3.json", R"({"name":"x","patch_length_m":0.1,"drainage_length_m":0.01,"slip_speed_m_s":10,"grooves":3})"))
                .find("unknown key \"grooves\""),
            std::string::npos);
  EXPECT_NE(message(file("t4.json", R"({"name":"x","patch_length_m":-1,"drainage_length_m":0.01,"slip_speed_m_s":10})")).find("patch_length_m"),
            std::string::npos);
  EXPECT_NE(message(file("t5.json", "not json")).find("not JSON"), std::string::npos);
  EXPECT_NE(message(dir + "absent.json").find("absent.json"), std::string::npos);
  EXPECT_THROW(check_water_film(0, "--water-film"), InputError);
  EXPECT_THROW(check_water_film(0.02, "--water-film"), InputError);
  EXPECT_THROW(check_water_film(NAN, "--water-film"), InputError);
  EXPECT_NO_THROW(check_water_film(0.5e-3, "--water-film"));
}

TEST(SkidNumbers, FilmOnASmoothRoadHydroplanesAndAThinOneDoesNot) {
  // A gentle one-band road under a thick film and a smooth tyre: the film does not drain at
  // high speed (friction falls, hydroplaning at a finite speed); under a film the texture holds
  // at equilibrium, the friction is the drained road's at every speed.
  const RoughnessSpectrum psd = band_spectrum(2e3, 2e5, 3e-21);  // rms ~ 20 um
  const Compound c = elastic_rubber(10e6);
  FrictionOptions opt;
  FilmScene film;
  film.test = tyre_test("e274-smooth");
  film.test.water_film = 1e-3;
  auto mu_h = [](const std::vector<double>& v) { return std::vector<double>(v.size(), 0.6); };
  const SkidCurve thick = skid_curve(psd, c, opt, film, {1.0, 30.0}, mu_h);
  EXPECT_GT(thick.points[0].mu, thick.points[1].mu);
  EXPECT_LT(thick.points[1].load_share, 0.5);
  EXPECT_TRUE(std::isfinite(thick.hydroplaning_kmh));
  EXPECT_TRUE(std::isfinite(thick.sp_kmh));
  LoadSeparation ls(psd, c, 30.0, 20);
  film.test.water_film = 0.5 * ls.separation(opt.pressure);
  const SkidCurve thin = skid_curve(psd, c, opt, film, {1.0, 30.0}, mu_h);
  EXPECT_NEAR(thin.points[1].load_share, 1.0, 1e-6);
  EXPECT_TRUE(std::isinf(thin.hydroplaning_kmh));
}

// --- command line -------------------------------------------------------------------------------

using wr_test::Cli;
using wr_test::CliRun;
namespace fs = std::filesystem;
class WetSpeedCli : public Cli {};

TEST_F(WetSpeedCli, FrictionPrintsSkidNumbersAndRefusesBadFilms) {
  ASSERT_EQ(run("synth --size 64 --dx 2e-4 --h0 1e-4 --seed 2 -q -o " + path("s.h5")).code, 0);
  const CliRun ok = run("friction " + path("s.h5") + " --speeds 1 17.9 --json " + path("f.json"));
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("speed constant Sp"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(slurp(path("f.json")));
  ASSERT_TRUE(j.contains("water_film"));
  EXPECT_EQ(j["water_film"]["test"], "e274-ribbed");
  EXPECT_EQ(j["water_film"]["skid"].size(), 17u);
  EXPECT_GT(j["water_film"]["sn"].get<double>(), 0);
  const struct {
    std::string args, names;
  } bad[] = {{"--water-film 0", "--water-film"},
             {"--water-film -1e-3", "--water-film"},
             {"--water-film 0.05", "--water-film"},
             {"--water-film nan", "--water-film"},
             {"--no-film --water-film 1e-3", "--water-film"},
             {"--speeds 0", "--speeds"},
             {"--speeds -3", "--speeds"},
             {"--test " + path("none.json"), "none.json"},
             {"--test e274-slick", "e274-slick"}};
  for (const auto& b : bad) {
    const CliRun r = run("friction " + path("s.h5") + " " + b.args + " --json " + path("bad.json"));
    EXPECT_EQ(r.code, 2) << b.args << ": " << r.err;
    EXPECT_NE(r.err.find(b.names), std::string::npos) << b.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(path("bad.json"))) << b.args;
  }
  std::ofstream(path("tyre.json")) << R"({"name":"x","patch_length_m":0.1,"slip_speed_m_s":10})";
  const CliRun r = run("friction " + path("s.h5") + " --test " + path("tyre.json") + " --json " + path("bad.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("drainage_length_m"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace wr
