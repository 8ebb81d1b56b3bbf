// Synthesis: rms height, spectrum shape, determinism, Nyquist refusal, prescribed moments.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "lib/core/errors.hpp"
#include "roads/height_stats.hpp"
#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"
#include "roads/synthesize.hpp"

namespace wr {
namespace {

SynthParams thesis_params(double hurst) {
  SynthParams p;  // thesis datasets: L = 0.03 m, N = 300, dx = 0.1 mm, q0 = 5 qL
  p.nx = p.ny = 300;
  p.dx = 1e-4;
  p.h0 = 0.708e-3;
  p.hurst = hurst;
  p.q0_ratio = 5;
  p.seed = 7;
  return p;
}

// Bar 1: measured h0 equals the prescribed one within 0.1% and the fitted H is within 0.05,
// for H = 0.5 ... 0.9 on the thesis's grid.
class SynthHurst : public ::testing::TestWithParam<double> {};

TEST_P(SynthHurst, RmsHeightAndHurstComeOut) {
  const SynthParams p = thesis_params(GetParam());
  const SynthResult r = synthesize(p);
  const double h0 = height_stats(r.map).sq;
  EXPECT_NEAR(h0 / p.h0, 1.0, 1e-3);
  // The lattice normalisation makes it exact to rounding; keep the tight check too.
  EXPECT_NEAR(h0 / p.h0, 1.0, 1e-10);
  const SpectrumResult s = analyze_spectrum(r.map);
  const PsdFit f = fit_self_affine(s.psd, s.nyquist, false);
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.hurst, p.hurst, 0.05);
  EXPECT_NEAR(f.q0 / r.psd.q0, 1.0, 0.25);
  EXPECT_GT(f.r2, 0.99);
  // eq. 4.4 alone misses on a finite lattice; it is reported, and it is a small error here.
  EXPECT_GT(std::abs(r.h0_eq44_on_lattice / p.h0 - 1), 1e-4);
  EXPECT_LT(std::abs(r.h0_eq44_on_lattice / p.h0 - 1), 0.05);
}

INSTANTIATE_TEST_SUITE_P(Hurst, SynthHurst, ::testing::Values(0.5, 0.6, 0.7, 0.8, 0.9));

TEST(Synthesize, SameSeedIsBitIdenticalOtherSeedIsNot) {
  SynthParams p = thesis_params(0.7);
  const SynthResult a = synthesize(p), b = synthesize(p);
  ASSERT_EQ(a.map.h.size(), b.map.h.size());
  EXPECT_EQ(0, std::memcmp(a.map.h.data(), b.map.h.data(), a.map.h.size() * sizeof(double)));
  p.seed = 8;
  const SynthResult c = synthesize(p);
  EXPECT_NE(0, std::memcmp(a.map.h.data(), c.map.h.data(), a.map.h.size() * sizeof(double)));
}

TEST(Synthesize, SurfaceIsRealPeriodicAndHasThePrescribedLatticePower) {
  SynthParams p = thesis_params(0.7);
  p.nx = 64;
  p.ny = 48;  // non-square, even and odd half-sizes
  const SynthResult r = synthesize(p);
  const SpectrumResult s = analyze_spectrum(r.map);
  EXPECT_NEAR(s.moments.m0, p.h0 * p.h0, 1e-12 * p.h0 * p.h0);
  double mean = 0;
  for (double v : r.map.h) mean += v;
  EXPECT_NEAR(mean / r.map.h.size(), 0.0, 1e-15);
}

TEST(Synthesize, OddGridSizesWork) {
  SynthParams p = thesis_params(0.7);
  p.nx = 51;
  p.ny = 37;
  const SynthResult r = synthesize(p);
  EXPECT_NEAR(height_stats(r.map).sq / p.h0, 1.0, 1e-10);
}

TEST(Synthesize, Q1AboveNyquistIsRefusedWithOversampleAdvice) {
  SynthParams p = thesis_params(0.7);
  p.q1 = 2 * std::numbers::pi / p.dx;  // thesis convention: twice Nyquist
  try {
    synthesize(p);
    FAIL() << "q1 above Nyquist was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--oversample 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Nyquist"), std::string::npos) << e.what();
  }
  p.oversample = 2;
  const SynthResult r = synthesize(p);
  EXPECT_EQ(r.map.nx, 600u);
  EXPECT_DOUBLE_EQ(r.map.dx, 0.5e-4);
}

// The expected forward-difference slope^2 of a lattice sampled from the waves with
// |q| <= q_top: each wave keeps its amplitude and, sampled at the grid points, its difference
// quotient (2/dx) sin(q_x dx / 2), whether it lies below Nyquist or aliases from above (sin^2 is
// periodic in q_x with period 2 pi / dx). Summed over the wave lattice independently of the
// synthesizer (its FFT, folding and rescale).
double expected_fd_slope(const SelfAffinePsd& psd, std::size_t n, double dx, double q_top) {
  const double qL = 2 * std::numbers::pi / (static_cast<double>(n) * dx);
  const long reach = static_cast<long>(std::ceil(q_top / qL));
  double sum = 0;
  for (long m = -reach; m <= reach; ++m)
    for (long k = -reach; k <= reach; ++k) {
      const double q = qL * std::hypot(double(m), double(k));
      if (q > q_top * (1 + 1e-12)) continue;
      const double sx = std::sin(m * qL * dx / 2), sy = std::sin(k * qL * dx / 2);
      sum += psd(q) * qL * qL * 4 / (dx * dx) * (sx * sx + sy * sy);
    }
  return std::sqrt(sum);
}

// The thesis's surfaces (sec. 4.1.1, Table 5.1) carry waves up to q1 = 2 pi/dx evaluated at the
// lattice points. Their lattice must be steeper than the band-limited one by what aliasing
// predicts (dataset A's spectrum: +8.5 %), with the same h0; oversampling is refused with it.
TEST(Synthesize, ThesisSamplingAliasesTheWavesAboveNyquist) {
  SynthParams p = thesis_params(0.7);
  p.h0 = 3.05e-4;
  const SynthResult band = synthesize(p);
  p.sampling = Sampling::thesis;
  const SynthResult thesis = synthesize(p);
  EXPECT_EQ(thesis.map.nx, 300u);
  EXPECT_DOUBLE_EQ(thesis.map.dx, 1e-4);
  EXPECT_NEAR(thesis.psd.q1, 2 * std::numbers::pi / p.dx, 1e-9 * thesis.psd.q1);
  // h0: the aliased waves land on occupied bins with random phases, so the power is exact only
  // in expectation; the waves above Nyquist hold ~0.3 % of it.
  EXPECT_NEAR(height_stats(thesis.map).sq / p.h0, 1.0, 0.01);
  double mean = 0;
  for (double v : thesis.map.h) mean += v;
  EXPECT_NEAR(mean / double(thesis.map.h.size()), 0.0, 1e-15);
  // Slopes against the independent sum; 2 %: the realisation's spread over ~1e5 waves (< 1 %).
  const double want_band = expected_fd_slope(band.psd, 300, p.dx, std::numbers::pi / p.dx);
  const double want_thesis = expected_fd_slope(thesis.psd, 300, p.dx, 2 * std::numbers::pi / p.dx);
  EXPECT_NEAR(rms_slope_finite_difference(band.map, 1) / want_band, 1.0, 0.02);
  EXPECT_NEAR(rms_slope_finite_difference(thesis.map, 1) / want_thesis, 1.0, 0.02);
  EXPECT_NEAR(want_thesis / want_band, 1.085, 0.01);
  // Its prescribed moments are Table 5.3's first row (alpha 88.9), the band-limited surface's
  // the row q1/q1hat = 1/2 (36.5).
  SelfAffinePsd cont = thesis.psd;
  cont.k = thesis.k_eq44;
  EXPECT_NEAR(cont.alpha(), 88.895, 0.9);
  cont = band.psd;
  cont.k = band.k_eq44;
  EXPECT_NEAR(cont.alpha(), 36.469, 0.4);

  p.oversample = 2;
  try {
    synthesize(p);
    FAIL() << "--oversample with --sampling thesis was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--oversample"), std::string::npos) << e.what();
  }
}

TEST(Synthesize, LowPassFractionRemovesPowerAboveTheCut) {
  SynthParams p = thesis_params(0.7);
  p.q1_fraction = 0.25;
  const SynthResult r = synthesize(p);
  const SpectrumResult s = analyze_spectrum(r.map);
  double above = 0, below = 0;
  for (std::size_t i = 0; i < s.psd.q.size(); ++i)
    (s.psd.q[i] > r.psd.q1_cut * 1.01 ? above : below) += s.psd.C[i] * s.psd.count[i];
  EXPECT_LT(above, 1e-20 * below);
  // Not renormalised: h0 drops below the prescribed full-spectrum value.
  EXPECT_LT(height_stats(r.map).sq, p.h0);
}

TEST(Synthesize, BadParametersAreRefused) {
  SynthParams p = thesis_params(0.7);
  p.dx = -1;
  EXPECT_THROW(synthesize(p), InputError);
  p = thesis_params(1.2);
  EXPECT_THROW(synthesize(p), InputError);
  p = thesis_params(0.7);
  p.nx = p.ny = 1;
  EXPECT_THROW(synthesize(p), InputError);
  p = thesis_params(0.7);
  p.nx = p.ny = std::size_t(1) << 22;  // 128 TiB
  EXPECT_THROW(synthesize(p), InputError);
}

// Bar 2: the prescribed continuous PSD with q1 = 2 pi / dx reproduces Table 5.3 within 1%
// (with its m4 misprints for 1/2 and 1/4 corrected: 5.04e8 and 8.31e7, see design.md).
TEST(PrescribedMoments, MatchThesisTable53) {
  const double L = 0.03, dx = 1e-4, qL = 2 * std::numbers::pi / L;
  const double q1 = 2 * std::numbers::pi / dx;
  struct Row {
    double fraction, m0, m2, m4, alpha;
  };
  const Row table[] = {{1.0, 5.001e-7, 4.146, 3.055e9, 88.895},
                       {0.5, 4.984e-7, 2.624, 5.039e8, 36.469},
                       {0.25, 4.939e-7, 1.620, 8.308e7, 15.627},
                       {0.125, 4.831e-7, 0.958, 1.367e7, 7.1916}};
  for (const Row& t : table) {
    const SelfAffinePsd p = SelfAffinePsd::from_eq44(0.708e-3, 0.7, qL, 5 * qL, q1, t.fraction);
    EXPECT_NEAR(p.m0() / t.m0, 1.0, 0.01) << "fraction " << t.fraction;
    EXPECT_NEAR(p.m2() / t.m2, 1.0, 0.01) << "fraction " << t.fraction;
    EXPECT_NEAR(p.m4() / t.m4, 1.0, 0.01) << "fraction " << t.fraction;
    EXPECT_NEAR(p.alpha() / t.alpha, 1.0, 0.01) << "fraction " << t.fraction;
  }
}

TEST(PrescribedMoments, Eq44MakesTheContinuousIntegralExact) {
  const double qL = 2 * std::numbers::pi / 0.03;
  for (double H : {0.3, 0.5, 0.7, 0.9}) {
    const SelfAffinePsd p = SelfAffinePsd::from_eq44(5e-4, H, qL, 5 * qL, 300 * qL);
    EXPECT_NEAR(p.m0(), 25e-8, 1e-12 * 25e-8);
  }
}

}  // namespace
}  // namespace wr
