// MPD pipeline (ISO 13473-1) on hand-made profiles with exact answers, and its filters.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "roads/expected_mpd.hpp"
#include "roads/mpd.hpp"
#include "roads/profile_filters.hpp"

namespace wr {
namespace {

constexpr double kPi = std::numbers::pi;

// A mirror-symmetric segment of n samples (zero least-squares slope by symmetry): flat at 0
// with one plateau of height `peak` and `w` samples in each half, mirrored. Its MSD is
// peak - mean = peak - 2 w peak / n.
std::vector<double> symmetric_segment(std::size_t n, std::size_t w, double peak, std::size_t at) {
  std::vector<double> h(n, 0.0);
  for (std::size_t i = at; i < at + w; ++i) {
    h[i] = peak;
    h[n - 1 - i] = peak;
  }
  return h;
}

TEST(MeanSegmentDepth, HandMadeSymmetricSegment) {
  const std::size_t n = 1000;
  const auto h = symmetric_segment(n, 50, 2e-3, 100);
  EXPECT_NEAR(mean_segment_depth(h.data(), n), 2e-3 - 2 * 50 * 2e-3 / n, 1e-15);
}

TEST(MeanSegmentDepth, SlopeIsRemovedPerSegment) {
  const std::size_t n = 1000;
  auto h = symmetric_segment(n, 50, 2e-3, 100);
  for (std::size_t i = 0; i < n; ++i) h[i] += 5e-3 + 1e-5 * double(i);  // offset and trend
  EXPECT_NEAR(mean_segment_depth(h.data(), n), 2e-3 - 2 * 50 * 2e-3 / n, 1e-14);
}

TEST(MeanSegmentDepth, DifferentPeaksInTheHalvesAreAveraged) {
  // First half: a 3 mm plateau of 10 samples centred 100 samples left of the middle; second
  // half: a 1 mm plateau of 20 samples centred 150 samples right of it. The moments balance
  // (3 x 10 x 100 = 1 x 20 x 150), so the least-squares slope is exactly zero and
  // MSD = ((3 - mean) + (1 - mean)) / 2 mm.
  const std::size_t n = 800;  // middle at 399.5
  std::vector<double> h(n, 0.0);
  for (std::size_t i = 295; i < 305; ++i) h[i] = 3e-3;  // centre 299.5
  for (std::size_t i = 540; i < 560; ++i) h[i] = 1e-3;  // centre 549.5
  const double mean = (10 * 3e-3 + 20 * 1e-3) / n;
  EXPECT_NEAR(mean_segment_depth(h.data(), n), 2e-3 - mean, 1e-15);
}

TEST(Mpd, PipelineOverSegmentsWithoutLowPass) {
  // 3 segments of 100 mm at 0.5 mm spacing, plus a 30 mm tail that must be ignored.
  const double dx = 0.5e-3;
  const std::size_t seg = 200;
  std::vector<double> h;
  const double peaks[3] = {1e-3, 2e-3, 4e-3};
  double expected = 0;
  for (double p : peaks) {
    const auto s = symmetric_segment(seg, 4, p, 20);
    h.insert(h.end(), s.begin(), s.end());
    expected += (p - 2 * 4 * p / seg) / 3;
  }
  h.insert(h.end(), 60, 9e-3);  // tail: a huge bump that would change the answer if used
  MpdOptions opt;
  opt.lowpass_wavelength = 0;
  MpdAccumulator acc;
  add_profile_segments(h, std::vector<unsigned char>(h.size(), 0), dx, opt, acc);
  const MpdResult r = summarize(acc, opt);
  EXPECT_EQ(r.valid_segments, 3u);
  EXPECT_TRUE(r.standard_baseline);
  EXPECT_NEAR(r.mpd, expected, 1e-15);
}

TEST(Mpd, SegmentWithTooManyDropoutsIsInvalid) {
  const double dx = 0.5e-3;
  const std::size_t seg = 200;
  std::vector<double> h;
  for (int k = 0; k < 2; ++k) {
    const auto s = symmetric_segment(seg, 4, 1e-3, 20);
    h.insert(h.end(), s.begin(), s.end());
  }
  std::vector<unsigned char> bad(h.size(), 0);
  for (std::size_t i = 250; i < 250 + 25; ++i) bad[i] = 1;  // 12.5% of segment 2
  MpdOptions opt;
  opt.lowpass_wavelength = 0;
  MpdAccumulator acc;
  add_profile_segments(h, bad, dx, opt, acc);
  const MpdResult r = summarize(acc, opt);
  EXPECT_EQ(r.segments, 2u);
  EXPECT_EQ(r.valid_segments, 1u);
  EXPECT_NEAR(r.mpd, 1e-3 - 2 * 4 * 1e-3 / seg, 1e-15);
}

TEST(Mpd, DropoutsUnderTheLimitAreInterpolated) {
  const std::size_t seg = 200;
  auto h = symmetric_segment(seg, 4, 1e-3, 20);
  std::vector<unsigned char> bad(seg, 0);
  // Dropouts in the flat part: interpolation restores the exact values, MSD unchanged.
  for (std::size_t i = 80; i < 90; ++i) {
    bad[i] = 1;
    h[i] = NAN;
  }
  MpdOptions opt;
  opt.lowpass_wavelength = 0;
  MpdAccumulator acc;
  add_profile_segments(h, bad, 0.5e-3, opt, acc);
  EXPECT_NEAR(summarize(acc, opt).mpd, 1e-3 - 2 * 4 * 1e-3 / seg, 1e-15);
}

TEST(Mpd, ShortProfileIsFlaggedNonStandard) {
  const auto h = symmetric_segment(300, 10, 1e-3, 30);  // 30 mm at 0.1 mm
  MpdOptions opt;
  opt.lowpass_wavelength = 0;
  MpdAccumulator acc;
  add_profile_segments(h, std::vector<unsigned char>(h.size(), 0), 1e-4, opt, acc);
  const MpdResult r = summarize(acc, opt);
  EXPECT_FALSE(r.standard_baseline);
  EXPECT_NEAR(r.baseline_used, 0.030, 1e-12);
  EXPECT_NE(r.note.find("non-standard baseline"), std::string::npos);
  EXPECT_NEAR(r.mpd, 1e-3 - 2 * 10 * 1e-3 / 300, 1e-15);
}

TEST(Mpd, EtdFormula) { EXPECT_NEAR(estimated_texture_depth(1e-3), 1.0e-3, 1e-15); }

TEST(ProfileFilters, LowPassAmplitudeResponseAndZeroPhase) {
  const double dx = 0.1e-3, lc = 2.5e-3;
  const std::size_t n = 20000;
  for (double lambda : {1.25e-3, 2.5e-3, 5e-3, 20e-3}) {
    std::vector<double> h(n);
    for (std::size_t i = 0; i < n; ++i) h[i] = std::sin(2 * kPi * i * dx / lambda);
    ASSERT_TRUE(lowpass_zero_phase(h.data(), n, dx, lc));
    // Project the middle onto sin and cos: the cos part is the phase error.
    double s = 0, c = 0, norm = 0;
    for (std::size_t i = n / 4; i < 3 * n / 4; ++i) {
      const double arg = 2 * kPi * i * dx / lambda;
      s += h[i] * std::sin(arg);
      c += h[i] * std::cos(arg);
      norm += std::sin(arg) * std::sin(arg);
    }
    // Bilinear warping: the digital response is that of tan(pi dx / lambda) over tan(pi dx / lc).
    const double ratio = std::tan(kPi * dx / lambda) / std::tan(kPi * dx / lc);
    const double expected = 1.0 / (1.0 + std::pow(ratio, 4));
    EXPECT_NEAR(s / norm, expected, 2e-3) << "lambda " << lambda;
    EXPECT_NEAR(c / norm, 0.0, 2e-3) << "lambda " << lambda;
  }
}

TEST(ProfileFilters, LowPassKeepsLinesExactly) {
  std::vector<double> h(5000);
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = 3e-3 - 2e-6 * double(i);
  const auto orig = h;
  ASSERT_TRUE(lowpass_zero_phase(h.data(), h.size(), 1e-4, 2.5e-3));
  for (std::size_t i = 0; i < h.size(); ++i) EXPECT_NEAR(h[i], orig[i], 1e-12);
}

TEST(ProfileFilters, LowPassRefusesCoarseSampling) {
  std::vector<double> h(100, 1.0);
  EXPECT_FALSE(lowpass_zero_phase(h.data(), h.size(), 1.5e-3, 2.5e-3));
}

TEST(ProfileFilters, SingleSampleSpikeIsFoundAndRemoved) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1e-5);
  std::vector<double> h(4000);
  double acc = 0;
  for (double& v : h) v = (acc += g(rng));  // smooth-ish random walk texture
  const double original = h[1234];
  h[1234] += 5e-3;
  std::vector<unsigned char> bad(h.size(), 0);
  EXPECT_EQ(mark_spikes(h.data(), bad.data(), h.size(), 0.0), 1u);
  EXPECT_TRUE(bad[1234]);
  interpolate_invalid(h.data(), bad.data(), h.size());
  EXPECT_NEAR(h[1234], original, 1e-4);
}

TEST(ExpectedMpd, ProfilePsdIntegratesToTheSurfaceVariance) {
  // integral of C1 over all qx equals h0^2 of the (plateau-extended) 2-D spectrum.
  const double qL = 2 * kPi / 0.03;
  SelfAffinePsd p = SelfAffinePsd::from_eq44(3e-4, 0.7, qL, 5 * qL, 150 * qL);
  SelfAffinePsd ext = p;
  ext.qL = 0;
  const double h0sq = ext.m0();
  double s = 0;
  const int n = 200000;
  const double dq = p.q1_cut / n;
  for (int i = 0; i < n; ++i) s += profile_psd(p, (i + 0.5) * dq) * dq;
  EXPECT_NEAR(2 * s / h0sq, 1.0, 2e-3);
}

}  // namespace
}  // namespace wr
