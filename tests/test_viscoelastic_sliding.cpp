// The exact rung of the hysteresis friction (lib/spectral/viscoelastic_sliding): steady sliding
// of a viscoelastic half-space over a periodic road, against closed forms and the elastic solver.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "lib/friction/compound.hpp"
#include "lib/friction/friction_scene.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "lib/spectral/viscoelastic_sliding.hpp"
#include "lib/core/errors.hpp"
#include "tests/cli_fixture.hpp"
#include "roads/band_limit.hpp"
#include "roads/synthesize.hpp"

namespace {

using namespace wr;

Compound tread() { return read_compound_json(default_compound_path()); }

// A compound without loss: the default's relaxed modulus alone.
Compound lossless() {
  Compound c = tread();
  for (PronyTerm& t : c.terms) t.de = 0;
  c.poisson = 0.49;  // the elastic solver's range
  return c;
}

HeightMap sinusoid(std::size_t nx, std::size_t ny, double period, int waves, double amplitude) {
  HeightMap m(nx, ny, period / double(nx), period / double(nx));
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      m(i, j) = amplitude * std::cos(2 * std::numbers::pi * waves * double(i) / double(nx));
  return m;
}

HeightMap road(std::size_t n, std::uint64_t seed, double h0 = 3e-5, double band = 16) {
  SynthParams s;
  s.nx = s.ny = n;
  s.dx = 0.03 / double(n);
  s.h0 = h0;
  s.hurst = 0.7;
  s.q0_ratio = 5;
  s.q1 = 2 * std::numbers::pi / 0.03 * band;  // 16 qL: 8 or more points per shortest wavelength
  s.seed = seed;
  s.threads = 1;
  return synthesize(s).map;
}

SlidingOptions options() {
  SlidingOptions o;
  o.tolerance = 1e-10;
  o.threads = 1;
  return o;
}

// Full contact on h cos(qx): p = sigma0 + (q h / 2) |E*| cos(qx + delta), so
// mu = <p h'> / sigma0 = (q h)^2 Im E* / (4 sigma0), E* = E / (1 - nu^2) (docs/friction-model.md).
TEST(ViscoelasticSliding, SinusoidInFullContactMatchesTheClosedForm) {
  const Compound c = tread();
  const double period = 0.01, amplitude = 2e-6, q = 2 * std::numbers::pi * 3 / period;
  for (double v : {1e-4, 1e-2, 1.0}) {
    const double e = std::abs(c.modulus(q * v, 20)) / (1 - c.poisson * c.poisson);
    const double sigma0 = 2 * q * amplitude * e / 2;  // twice the full-contact threshold
    for (std::size_t ny : {std::size_t(1), std::size_t(4)}) {
      ViscoelasticSliding s(sinusoid(64, ny, period, 3, amplitude), c, 20, options());
      const SlidingResult r = s.solve(v, sigma0);
      ASSERT_TRUE(r.converged) << r.message;
      const double exact = sinusoid_full_contact_mu(c, 20, q, amplitude, v, sigma0);
      EXPECT_GT(exact, 0);
      EXPECT_NEAR(r.mu, exact, 1e-6 * exact) << "v " << v << " ny " << ny;
      EXPECT_NEAR(r.mu_dissipation, exact, 1e-6 * exact);
      EXPECT_DOUBLE_EQ(r.area_fraction, 1.0);
      EXPECT_NEAR(r.dissipation, r.mu * sigma0 * v, 1e-6 * r.dissipation);
    }
  }
}

// Lossless rubber: no dissipation, and the contact of the elastic solver (normal_contact.hpp).
TEST(ViscoelasticSliding, LosslessCompoundHasNoFrictionAndTheElasticContact) {
  const Compound c = lossless();
  const HeightMap m = road(128, 3, 3e-4);
  ViscoelasticSliding s(m, c, 20, options());
  const double sigma0 = 0.3e6;
  const SlidingResult r = s.solve(1.0, sigma0);
  ASSERT_TRUE(r.converged) << r.message;
  SpectralNormalContact elastic(m, ElasticBody{c.e_relaxed, c.poisson}, 1, FftPlanning::estimate);
  SpectralOptions eo;
  eo.tolerance = 1e-10;
  eo.precision = SpectralOptions::Precision::full;
  const SpectralNormalResult e = elastic.solve_load(sigma0, eo);
  ASSERT_TRUE(e.converged) << e.message;
  EXPECT_GT(r.area_fraction, 0.02);
  EXPECT_LT(r.area_fraction, 0.5);
  EXPECT_DOUBLE_EQ(r.area_fraction, e.area_fraction);
  double dp = 0, pmax = 0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    dp = std::max(dp, std::abs(s.pressure()[k] - elastic.pressure()[k]));
    pmax = std::max(pmax, elastic.pressure()[k]);
  }
  EXPECT_LT(dp, 1e-6 * pmax);
  // The dissipation vanishes to round-off; the force on the sloped road only in the continuum
  // (a sub-grid shift is no symmetry of the grid): its residual is the contact edges' error.
  EXPECT_LT(std::abs(r.mu_dissipation), 1e-14);
  std::printf("lossless: mu on the sloped road %.2e, dissipation mu %.2e, A/A0 %.4f\n", r.mu, r.mu_dissipation, r.area_fraction);
  EXPECT_LT(std::abs(r.mu), 1e-3);
}

// Full contact on a rough road: the tangential force on the road equals the dissipation.
TEST(ViscoelasticSliding, DissipationIdentityHoldsInFullContact) {
  const Compound c = tread();
  const HeightMap m = road(64, 5, 2e-6);
  ViscoelasticSliding s(m, c, 20, options());
  for (double v : {1e-3, 0.1, 10.0}) {
    const SlidingResult r = s.solve(v, 1e6);
    ASSERT_TRUE(r.converged) << r.message;
    ASSERT_DOUBLE_EQ(r.area_fraction, 1.0);
    EXPECT_GT(r.mu, 0);
    EXPECT_LT(r.identity_residual, 1e-6) << "v " << v;
    EXPECT_NEAR(r.dissipation, r.mu * 1e6 * v, 1e-6 * r.dissipation);
  }
}

// Partial contact: the identity's residual is the contact edges' discretisation, shrinking as
// the same band is resolved by more points; mu converges with it.
TEST(ViscoelasticSliding, PartialContactConvergesWithTheGrid) {
  const Compound c = tread();
  const HeightMap coarse = road(64, 3, 3e-4, 8);
  std::vector<double> mu, residual;
  for (std::size_t refine : {std::size_t(1), std::size_t(2), std::size_t(4)}) {
    ViscoelasticSliding s(band_limited(coarse, 1e300, refine, 1), c, 20, options());
    const SlidingResult r = s.solve(0.1, 0.3e6);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_GT(r.area_fraction, 0.01);
    EXPECT_LT(r.area_fraction, 0.3);
    mu.push_back(r.mu);
    residual.push_back(r.identity_residual);
  }
  EXPECT_LT(residual[2], residual[0] / 3);
  EXPECT_LT(std::abs(mu[2] - mu[1]), std::abs(mu[1] - mu[0]));  // converging
  EXPECT_LT(std::abs(mu[2] - mu[1]) / mu[2], 0.05);
}

// The road mirrored in x with the rubber sliding the other way is the same problem: sliding
// along +x over the mirror must give the friction of the original slid along -x, which by
// symmetry of an isotropic statistics is not the same map's; but mirroring twice is identity,
// and mirroring the road reverses the sign of no scalar: mu, A/A0 and the dissipation are
// invariant under the mirror in y (the sliding direction unchanged).
TEST(ViscoelasticSliding, MirrorAcrossTheSlidingDirectionChangesNothing) {
  const Compound c = tread();
  const HeightMap m = road(64, 7, 3e-4, 8);
  HeightMap mirrored = m;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) mirrored(i, j) = m(i, (m.ny - j) % m.ny);
  ViscoelasticSliding a(m, c, 20, options()), b(mirrored, c, 20, options());
  const SlidingResult ra = a.solve(0.01, 0.3e6), rb = b.solve(0.01, 0.3e6);
  ASSERT_TRUE(ra.converged && rb.converged);
  EXPECT_NEAR(ra.mu, rb.mu, 1e-8 * ra.mu);
  EXPECT_DOUBLE_EQ(ra.area_fraction, rb.area_fraction);
}

TEST(ViscoelasticSliding, SameAnswerOnOneAndTwoThreads) {
  const Compound c = tread();
  const HeightMap m = road(128, 9, 3e-4, 16);
  SlidingOptions one = options(), two = options();
  two.threads = 2;
  ViscoelasticSliding a(m, c, 20, one), b(m, c, 20, two);
  const SlidingResult ra = a.solve(0.1, 0.3e6), rb = b.solve(0.1, 0.3e6);
  EXPECT_EQ(ra.iterations, rb.iterations);
  EXPECT_DOUBLE_EQ(ra.mu, rb.mu);
  EXPECT_DOUBLE_EQ(ra.area_fraction, rb.area_fraction);
}

TEST(ViscoelasticSliding, AnUnfinishedSolveSaysSo) {
  const Compound c = tread();
  SlidingOptions o = options();
  o.max_iterations = 3;
  ViscoelasticSliding s(road(128, 3, 3e-4, 16), c, 20, o);
  const SlidingResult r = s.solve(1.0, 0.3e6);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("did not converge in 3 iterations"), std::string::npos) << r.message;
  EXPECT_THROW(s.solve(0, 0.3e6), std::invalid_argument);
  EXPECT_THROW(s.solve(1, -1), std::invalid_argument);
  HeightMap open = road(32, 1, 1e-5, 8);
  open.periodic = false;
  EXPECT_THROW(ViscoelasticSliding(open, c, 20, o), std::invalid_argument);
  EXPECT_THROW(ViscoelasticSliding(road(32, 1, 1e-5, 8), c, -200, o), InputError);  // below the WLF pole
}

// Partial contact against the closed-form steady state of a rigid cylinder on a standard linear
// solid in plane strain (Hunter, J. Appl. Mech. 28, 611 (1961)): the rolling resistance e/a0 =
// mu R / a0 and the contact half-width, as re-derived and checked against an independent
// real-space boundary-element solution (docs/validation.md, "The exact rung"; the table there
// gives the source of each number). The cylinder is the crest of a long cosine, period 80 a0,
// whose curvature at the crest is 1/R (its x^4 term changes the profile by 5e-4 over the
// contact); the profile, being one Fourier mode, has an exact spectral slope.
TEST(ViscoelasticSliding, RollingCylinderOnAStandardLinearSolidMatchesHunter) {
  struct Case {
    double k, vt_over_a0, mu_r_over_a0, a_over_a0, b_over_a0;
  };
  const double e_relaxed = 6e6, nu = 0.5, radius = 0.01, a0 = 1e-3, v = 1.0;
  const double e_star = e_relaxed / (1 - nu * nu);
  const double load = std::numbers::pi * e_star * a0 * a0 / (4 * radius);  // N/m: the relaxed Hertz half-width a0
  const double period = 80 * a0;
  const std::size_t n = 16384;
  for (const Case& c : {Case{10, 1.0, 0.46391, 0.91834, 0.28349}, Case{3, 1.1359, 0.29110, 0.91972, 0.48307}}) {
    Compound sls = tread();
    sls.e_relaxed = e_relaxed;
    sls.poisson = nu;
    const double retardation = c.vt_over_a0 * a0 / v, relaxation = retardation / c.k;
    sls.terms = {PronyTerm{relaxation, (c.k - 1) * e_relaxed}};
    HeightMap m(n, 1, period / double(n), period / double(n), HeightMap::Kind::profile);
    const double amplitude = period * period / (4 * std::numbers::pi * std::numbers::pi * radius);
    for (std::size_t i = 0; i < n; ++i) m.h[i] = amplitude * std::cos(2 * std::numbers::pi * (double(i) / double(n) - 0.5));
    ViscoelasticSliding s(m, sls, sls.reference_temperature, options());
    const SlidingResult r = s.solve(v, load / period);
    ASSERT_TRUE(r.converged) << r.message;
    const double mu_r_over_a0 = r.mu * radius / a0;
    EXPECT_NEAR(mu_r_over_a0, c.mu_r_over_a0, 0.01 * c.mu_r_over_a0) << "k " << c.k;
    // The contact's ends, measured from the crest (the leading edge is upstream, at -a).
    double lead = 0, trail = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (s.pressure()[i] > 0) {
        const double x = (double(i) - double(n) / 2) * m.dx / a0;
        lead = std::max(lead, -x);
        trail = std::max(trail, x);
      }
    const double cell = m.dx / a0;
    std::printf("Hunter k %g, VT/a0 %g: mu R/a0 %.5f (closed form %.5f), a/a0 %.4f (%.5f), b/a0 %.4f (%.5f), %d iterations\n", c.k,
                c.vt_over_a0, mu_r_over_a0, c.mu_r_over_a0, lead, c.a_over_a0, trail, c.b_over_a0, r.iterations);
    EXPECT_NEAR(lead, c.a_over_a0, 2 * cell) << "k " << c.k;
    EXPECT_NEAR(trail, c.b_over_a0, 2 * cell) << "k " << c.k;
    EXPECT_LT(r.identity_residual, 0.01);
  }
}

// The band limit: sampled back on the coarse points, the refined map is the coarse one.
TEST(BandLimit, RefinedMapPassesThroughTheCoarsePoints) {
  const HeightMap m = road(64, 3, 3e-4, 8);
  const HeightMap f = band_limited(m, 1e300, 4, 1);
  ASSERT_EQ(f.nx, 256u);
  double err = 0, top = 0;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      err = std::max(err, std::abs(f(4 * i, 4 * j) - m(i, j)));
      top = std::max(top, std::abs(m(i, j)));
    }
  EXPECT_LT(err, 1e-12 * top);
  // A circular band below the map's: the waves above it are gone.
  const HeightMap low = band_limited(m, 2 * std::numbers::pi / 0.03 * 4, 1, 1);
  double power = 0;
  for (double h : low.h) power += h * h;
  EXPECT_GT(power, 0);
  EXPECT_LT(power, [&] {
    double p = 0;
    for (double h : m.h) p += h * h;
    return p;
  }());
}

}  // namespace

// The rung on the command line: `friction --model viscoelastic|auto` and the sweeps.
namespace {

class ExactRungCli : public wr_test::Cli {};

TEST_F(ExactRungCli, FrictionRunsTheExactRungBesidePerssonOnTheSameBand) {
  ASSERT_EQ(run("synth --size 64 --dx 4.7e-4 --h0 3e-4 --seed 2 -q -o " + path("s.h5")).code, 0);
  const auto r = run("friction " + path("s.h5") + " --model viscoelastic --no-film --speeds 0.01 1 --exact-refine 2 --json " +
                     path("f.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Persson mu"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(path("f.json")));
  EXPECT_EQ(j["rung"], "viscoelastic");
  EXPECT_FALSE(j["extrapolated"].get<bool>());
  EXPECT_EQ(j["exact"]["grid"][0], 128);
  EXPECT_TRUE(j["exact"]["converged"].get<bool>());
  const double mu = j["speeds"][1]["mu"].get<double>(), pe = j["exact"]["persson_same_band"]["speeds"][1]["mu"].get<double>();
  EXPECT_GT(mu, 0.01);
  EXPECT_GT(pe / mu, 0.5);  // the two rungs agree within a factor 2 (docs/validation.md)
  EXPECT_LT(pe / mu, 2.0);
  EXPECT_GT(j["speeds"][1]["mu"].get<double>(), j["speeds"][0]["mu"].get<double>());
}

TEST_F(ExactRungCli, TheReportShowsTheRungBesidePerssonAndTheLadder) {
  ASSERT_EQ(run("synth --size 48 --dx 6.25e-4 --h0 3e-4 --seed 4 -q -o " + path("s.h5")).code, 0);
  ASSERT_EQ(run("friction " + path("s.h5") + " --model viscoelastic --speeds 0.01 1 --exact-refine 2 -q --out " + path("f.h5")).code, 0);
  const auto r = run("report --friction " + path("f.h5") + " -q -o " + path("r.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = slurp(path("r.html"));
  EXPECT_NE(html.find("The exact rung: steady viscoelastic sliding on the map"), std::string::npos);
  EXPECT_NE(html.find("Persson on the same band"), std::string::npos);
  EXPECT_NE(html.find("speed against accuracy of the friction ladder"), std::string::npos);
}

TEST_F(ExactRungCli, AutoKeepsPerssonUnlessItsCheckFailsOnAMeasuredBand) {
  ASSERT_EQ(run("synth --size 64 --dx 4.7e-4 --h0 3e-4 --seed 2 -q -o " + path("s.h5")).code, 0);
  auto rung = [&](const std::string& extra) {
    const auto r = run("friction " + path("s.h5") + " --no-film --speeds 0.1 --exact-refine 1 -q --json " + path("a.json") + " " + extra);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(slurp(path("a.json")))["rung"].get<std::string>();
  };
  EXPECT_EQ(rung(""), "persson");                       // default pressure: the check passes
  EXPECT_EQ(rung("--pressure 1e6"), "persson");         // fails, but q1 is extrapolated past the map
  EXPECT_EQ(rung("--pressure 1e6 --q1 5000"), "viscoelastic");  // fails on the map's own band
  EXPECT_EQ(rung("--pressure 1e6 --q1 5000 --model persson"), "persson");
}

TEST_F(ExactRungCli, RefusesWhatTheExactRungCannotDo) {
  ASSERT_EQ(run("synth --size 32 --dx 9e-4 --h0 3e-4 --seed 2 -q -o " + path("s.h5")).code, 0);
  const std::string base = "friction " + path("s.h5") + " --no-film --speeds 0.1 --json " + path("x.json") + " ";
  for (const auto& [args, option] : std::vector<std::pair<std::string, std::string>>{
           {"--model viscoelastic --q1 1e6", "--q1"},
           {"--model viscoelastic --flash-temperature", "--flash-temperature"},
           {"--model bogus", "--model"},
           {"--model viscoelastic --exact-refine 0", "--exact-refine"}}) {
    const auto r = run(base + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("x.json")));
  }
}

TEST_F(ExactRungCli, SweepsTakeTheRung) {
  const auto r = run("sweep-coverage --model hysteresis --hysteresis-model viscoelastic --exact-refine 1 --size 48 --coverages 0 0.3 "
                     "--no-film -q --out " + path("sw.h5") + " --json " + path("sw.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(path("sw.json")));
  ASSERT_FALSE(j["runs"].empty());
  for (const auto& run : j["runs"]) {
    EXPECT_EQ(run["contact"]["rung"], "viscoelastic") << run.dump();
    EXPECT_TRUE(run["contact"].contains("mu_persson_same_band"));
  }
}

}  // namespace
