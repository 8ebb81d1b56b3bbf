// MPD pipeline (ISO 13473-1) on hand-made profiles with exact answers, and its filters.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "roads/expected_mpd.hpp"
#include "roads/mpd.hpp"
#include "roads/profile_filters.hpp"
#include "roads/reference_plates.hpp"
#include "roads/surface_file.hpp"
#include "tests/cli_fixture.hpp"

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
  opt.spike_alpha = 0;  // the plateaus' 2-4 mm steps would be Annex E spikes at 0.5 mm
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
  opt.spike_alpha = 0;
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
  opt.resample = false;  // the raw 0.1 mm samples, as the hand answer counts them
  MpdAccumulator acc;
  add_profile_segments(h, std::vector<unsigned char>(h.size(), 0), 1e-4, opt, acc);
  const MpdResult r = summarize(acc, opt);
  EXPECT_FALSE(r.standard_baseline);
  EXPECT_NEAR(r.baseline_used, 0.030, 1e-12);
  EXPECT_NE(r.note.find("non-standard baseline"), std::string::npos);
  EXPECT_NE(r.note.find("not resampled"), std::string::npos);
  EXPECT_NEAR(r.mpd, 1e-3 - 2 * 10 * 1e-3 / 300, 1e-15);
}

TEST(Mpd, EtdFormula) { EXPECT_NEAR(estimated_texture_depth(1e-3), 1.0e-3, 1e-15); }

// Annex D: each pass is -3 dB at its cut-off (gain 1 / sqrt(2)); forward and backward the
// phase is zero and the gain squared, so the zero-phase filter is -6 dB there. Measured on
// sinusoids at the standard's spacing and cut-offs (2.4 mm low-pass, 174.2 mm high-pass).
TEST(ProfileFilters, ButterworthGainsAndZeroPhase) {
  const double dx = 0.5e-3;
  EXPECT_NEAR(butterworth_gain(dx, 2.4e-3, 2.4e-3, PassBand::lowpass), 1 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(butterworth_gain(dx, 174.2e-3, 174.2e-3, PassBand::highpass), 1 / std::sqrt(2.0), 1e-12);
  struct Case {
    PassBand band;
    double cutoff, lambda;
  };
  const std::size_t n = 40000;  // 20 m
  for (const Case& c : {Case{PassBand::lowpass, 2.4e-3, 1.5e-3}, Case{PassBand::lowpass, 2.4e-3, 2.4e-3},
                        Case{PassBand::lowpass, 2.4e-3, 5e-3}, Case{PassBand::highpass, 174.2e-3, 100e-3},
                        Case{PassBand::highpass, 174.2e-3, 174.2e-3}, Case{PassBand::highpass, 174.2e-3, 400e-3}}) {
    std::vector<double> h(n);
    for (std::size_t i = 0; i < n; ++i) h[i] = std::sin(2 * kPi * double(i) * dx / c.lambda);
    ASSERT_TRUE(butterworth_zero_phase(h.data(), n, dx, c.cutoff, c.band));
    // Project the middle onto sin and cos: the cos part is the phase error.
    double s = 0, co = 0, norm = 0;
    for (std::size_t i = n / 4; i < 3 * n / 4; ++i) {
      const double arg = 2 * kPi * double(i) * dx / c.lambda;
      s += h[i] * std::sin(arg);
      co += h[i] * std::cos(arg);
      norm += std::sin(arg) * std::sin(arg);
    }
    const double g = butterworth_gain(dx, c.cutoff, c.lambda, c.band);
    EXPECT_NEAR(s / norm, g * g, 2e-3) << "lambda " << c.lambda;
    EXPECT_NEAR(co / norm, 0.0, 2e-3) << "lambda " << c.lambda;
    if (c.lambda == c.cutoff) EXPECT_NEAR(20 * std::log10(s / norm), -6.02, 0.05);
  }
}

// A constant passes exactly (steady-state start); a line too, except within a few cut-off
// wavelengths of the ends, where the short odd extension of the reference implementations
// leaves a transient (the standard's filter, not an error of this one).
TEST(ProfileFilters, LowPassKeepsConstantsExactlyAndLinesAwayFromTheEnds) {
  const double dx = 5e-4, lc = 2.4e-3;
  std::vector<double> c(5000, 3e-3);
  ASSERT_TRUE(butterworth_zero_phase(c.data(), c.size(), dx, lc, PassBand::lowpass));
  for (double v : c) EXPECT_NEAR(v, 3e-3, 1e-15);
  std::vector<double> h(5000);
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = 3e-3 - 2e-6 * double(i);
  const auto orig = h;
  ASSERT_TRUE(butterworth_zero_phase(h.data(), h.size(), dx, lc, PassBand::lowpass));
  const std::size_t edge = std::size_t(10 * lc / dx);
  for (std::size_t i = edge; i + edge < h.size(); ++i) EXPECT_NEAR(h[i], orig[i], 1e-12) << i;
}

TEST(ProfileFilters, LowPassRefusesCoarseSampling) {
  std::vector<double> h(100, 1.0);
  EXPECT_FALSE(butterworth_zero_phase(h.data(), h.size(), 1.5e-3, 2.4e-3, PassBand::lowpass));
}

// Clause 7.3 by hand: linear inside, the nearest valid value held at the ends.
TEST(ProfileFilters, DropoutsAreInterpolatedAndHeldAtTheEnds) {
  std::vector<double> h{NAN, 0.1, NAN, 0.4, NAN};
  const std::vector<unsigned char> bad{1, 0, 1, 0, 1};
  ASSERT_TRUE(interpolate_invalid(h.data(), bad.data(), h.size()));
  const std::vector<double> expected{0.1, 0.1, 0.25, 0.4, 0.4};
  for (std::size_t i = 0; i < h.size(); ++i) EXPECT_NEAR(h[i], expected[i], 1e-15) << i;
}

// Clause 7.4 by hand: raw samples every 0.25 at x = 0 ... 2.5, resampled to 0.5. Bin k holds
// x in ((k - 1) 0.5, k 0.5], the first also x = 0: means 0.2, 0.15, 0.15, 0, 0.3.
TEST(ProfileFilters, ResamplingAveragesTheRawSamplesOfEachBin) {
  const std::vector<double> h{0.3, 0.1, 0.2, 0.2, 0.1, 0.2, 0.1, -0.1, 0.1, 0.1, 0.5};
  std::vector<unsigned char> drop(h.size(), 0);
  drop[7] = 1;
  const ResampledProfile r = resample_bin_average(h.data(), drop.data(), h.size(), 0.25, 0.5);
  const std::vector<double> expected{0.2, 0.15, 0.15, 0.0, 0.3};
  ASSERT_EQ(r.h.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(r.h[k], expected[k], 1e-15) << k;
  EXPECT_EQ(r.raw, (std::vector<unsigned>{3, 2, 2, 2, 2}));
  EXPECT_EQ(r.dropouts, (std::vector<unsigned>{0, 0, 0, 1, 0}));
}

// Annex E by hand (spacing 0.1, alpha 3: neighbours 0.3 apart or more are both flagged), then
// interpolated like dropouts.
TEST(ProfileFilters, SpikesFlagBothNeighboursAndAreInterpolated) {
  struct Case {
    std::vector<double> in, out;
  };
  for (const Case& c : {Case{{0.1, 0, 0.3, 0, 0.1}, {0.1, 0.1, 0.1, 0.1, 0.1}},
                        Case{{0.3, 0, 0.1, 0, 0.3}, {0.1, 0.1, 0.1, 0.1, 0.1}},
                        Case{{0.3, 0, 0.2, 0, 0.3, 0, -0.2, 0, 0.3}, {0.2, 0.2, 0.2, 0.1, 0, -0.1, -0.2, -0.2, -0.2}}}) {
    std::vector<double> h = c.in;
    std::vector<unsigned char> bad(h.size(), 0);
    EXPECT_GT(mark_spikes(h.data(), bad.data(), h.size(), 0.1, 3.0), 0u);
    ASSERT_TRUE(interpolate_invalid(h.data(), bad.data(), h.size()));
    for (std::size_t i = 0; i < h.size(); ++i) EXPECT_NEAR(h[i], c.out[i], 1e-15) << i;
  }
}

// The whole pipeline, filters off, by hand: a square wave of +-a (period 10 mm) sampled every
// 0.1 mm with its levels constant over each 0.5 mm bin, so the bin averages are the wave
// itself; three 100 mm segments and a tail. Without slope suppression (continuous method, no
// high-pass) each half's peak is a and the mean 0: MSD = MPD = a. One raw sample spiked flags
// three resampled samples (1.5 % of its segment, valid) and is interpolated away; ten spikes in
// the second segment (15 %) make it invalid, and 4 % raw dropouts inside a plateau of the third
// (interpolated, under the 10 % rule) leave it valid.
TEST(Mpd, SquareWaveThroughEveryStepByHand) {
  const double a = 0.5e-3, dx = 0.1e-3, spacing = 0.5e-3;
  const std::size_t n = 3200;  // 320 mm: three segments and a 20 mm tail
  std::vector<double> h(n);
  std::vector<unsigned char> drop(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t bin = std::max<std::size_t>(1, std::size_t(std::ceil(double(i) * dx / spacing - 1e-9)));
    h[i] = ((bin - 1) / 10) % 2 == 0 ? a : -a;
  }
  // A 25 mm raw spike is 5 mm in its bin's average: all inside plateaus, so that the
  // interpolation across the three flagged bins restores the wave exactly.
  h[473] += 25e-3;                                                      // segment 1, bin 95
  for (std::size_t k = 0; k < 10; ++k) h[1000 + 50 * k + 20] += 25e-3;  // segment 2: 10 spikes
  for (std::size_t i = 2105; i < 2145; ++i) drop[i] = 1;                // segment 3: 40 of 1000 raw
  MpdOptions opt;
  opt.method = MpdMethod::continuous;
  opt.highpass_wavelength = 0;
  opt.lowpass_wavelength = 0;
  MpdAccumulator acc;
  add_profile_segments(h, drop, dx, opt, acc);
  const MpdResult r = summarize(acc, opt);
  EXPECT_NEAR(r.spacing, spacing, 1e-15);
  EXPECT_EQ(r.spikes, 33u);
  EXPECT_EQ(r.segments, 3u);
  EXPECT_EQ(r.valid_segments, 2u);
  EXPECT_TRUE(r.valid);
  EXPECT_NEAR(r.mpd, a, 1e-15);
  EXPECT_NEAR(r.mpd_std, 0.0, 1e-15);
}

// Slope suppression (spot method) by hand: a sawtooth of period 10 mm (teeth f_j = A (j / 20 -
// 1/2), j = 0 ... 19) on a 2 % grade, sampled at the standard's 0.5 mm, two segments of ten
// teeth, 10 dropouts (5 %) inside one tooth's rise. The grade is removed exactly; over the
// segment's samples i = 0 ... 199 (centre c = 99.5) the teeth's own least-squares slope is
// b = sum (i - c) f_i / sum (i - c)^2 = 332.5 A / 666650 and their mean -A / 40. Each half's
// highest residual is at its first tooth top (i = 19 and 119, f = 0.45 A):
// MSD = 0.45 A + A / 40 + b (80.5 - 19.5) / 2 = 0.475 A + 30.5 b.
TEST(Mpd, SawtoothOnAGradeWithDropoutsBySlopeSuppression) {
  const double A = 1e-3, dx = 0.5e-3;
  const std::size_t n = 400;
  std::vector<double> h(n);
  for (std::size_t i = 0; i < n; ++i) h[i] = A * (double(i % 20) / 20.0 - 0.5) + 0.02 * double(i) * dx;
  std::vector<unsigned char> drop(n, 0);
  for (std::size_t i = 205; i < 215; ++i) {  // inside one tooth's rise: linear, restored exactly
    drop[i] = 1;
    h[i] = NAN;
  }
  MpdOptions opt;
  opt.lowpass_wavelength = 0;  // the teeth's 1 mm drops stay under Annex E's 1.5 mm
  MpdAccumulator acc;
  add_profile_segments(h, drop, dx, opt, acc);
  const MpdResult r = summarize(acc, opt);
  EXPECT_EQ(r.spikes, 0u);
  ASSERT_EQ(r.valid_segments, 2u);
  EXPECT_NEAR(r.mpd, 0.475 * A + 30.5 * 332.5 * A / 666650, 1e-14);
  EXPECT_NEAR(r.mpd_std, 0.0, 1e-14);
}

// A road texture: a +-0.5 mm square wave of period 10 mm, every 0.1 mm.
std::vector<double> square_road(std::size_t n) {
  std::vector<double> h(n);
  for (std::size_t i = 0; i < n; ++i) h[i] = (i / 50) % 2 == 0 ? 0.5e-3 : -0.5e-3;
  return h;
}

// Calibration plates at both ends of a record (30 mm at +20 mm with 0.1 mm of noise, 40 mm at
// -15 mm) are found, cut with the 2 mm margin over their edges and reported; the MPD is then
// that of the road alone with the same margins trimmed.
TEST(ReferencePlates, PlatesAtBothEndsAreCutAndReported) {
  const double dx = 0.1e-3;
  const std::vector<double> road = square_road(3000);  // 300 mm
  std::vector<double> h;
  for (std::size_t i = 0; i < 300; ++i) h.push_back(20e-3 + (i % 3 == 0 ? 0.1e-3 : 0.0));
  h.insert(h.end(), road.begin(), road.end());
  h.insert(h.end(), 400, -15e-3);
  std::vector<unsigned char> drop(h.size(), 0);
  drop[100] = 1;  // a dropout on the plate does not end it
  const PlateCut cut = find_reference_plates(h.data(), drop.data(), h.size(), dx);
  EXPECT_EQ(cut.start, 300u + 20u);
  EXPECT_EQ(cut.end, 400u + 20u);

  MpdOptions opt;
  opt.cut_plates = true;
  MpdAccumulator with, bare;
  add_profile_segments(h, drop, dx, opt, with);
  const MpdResult r = summarize(with, opt);
  EXPECT_NEAR(r.plate_start, 32e-3, 1e-12);
  EXPECT_NEAR(r.plate_end, 42e-3, 1e-12);
  EXPECT_NE(r.note.find("reference plates cut: 32.0 mm at the start, 42.0 mm at the end"), std::string::npos) << r.note;
  const std::vector<double> trimmed(road.begin() + 20, road.end() - 20);
  add_profile_segments(trimmed, std::vector<unsigned char>(trimmed.size(), 0), dx, opt, bare);
  EXPECT_EQ(summarize(bare, opt).plate_start, 0.0);
  EXPECT_NEAR(r.mpd, summarize(bare, opt).mpd, 1e-15);
}

// A road that starts on a flat stretch at its own level, or a record flat throughout, is not cut.
TEST(ReferencePlates, FlatRoadAtItsOwnLevelIsNotAPlate) {
  const double dx = 0.1e-3;
  std::vector<double> h(200, 0.2e-3);  // 20 mm flat, 0.2 mm off the road's median: no step
  const std::vector<double> road = square_road(3000);
  h.insert(h.end(), road.begin(), road.end());
  const std::vector<unsigned char> drop(h.size(), 0);
  const PlateCut cut = find_reference_plates(h.data(), drop.data(), h.size(), dx);
  EXPECT_EQ(cut.start, 0u);
  EXPECT_EQ(cut.end, 0u);
  const std::vector<double> flat(2000, 1e-3);
  const PlateCut none = find_reference_plates(flat.data(), drop.data(), flat.size(), dx);
  EXPECT_EQ(none.start + none.end, 0u);
}

// A map's rows and columns are reported apart (as a CTMeter does) and together.
TEST(Mpd, MapReportsAlongXAndAlongYApart) {
  // Rows carry a 0.5 mm square wave along x, columns are flat along y except for that pattern
  // (each column constant): MPD along y is 0, along x is a.
  HeightMap m;
  m.nx = m.ny = 220;  // 110 mm at 0.5 mm: one segment each way
  m.dx = m.dy = 0.5e-3;
  m.h.resize(m.nx * m.ny);
  const double a = 0.5e-3;
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix) m.h[iy * m.nx + ix] = (ix / 10) % 2 == 0 ? a : -a;
  MpdOptions opt;
  opt.method = MpdMethod::continuous;
  opt.highpass_wavelength = 0;
  opt.lowpass_wavelength = 0;
  const MpdResult r = mpd_of_map(m, std::vector<unsigned char>(m.h.size(), 0), opt, 1);
  EXPECT_NEAR(r.mpd_x, a, 1e-15);
  EXPECT_NEAR(r.mpd_y, 0.0, 1e-15);
  EXPECT_NEAR(r.mpd, a / 2, 1e-15);
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

// ---- MPD per evaluation length (issue 54 bar 2; ISO 13473-1:2019 continuous records) ----

// A record of twelve 100 mm segments (each the symmetric plateau segment, MSD = p (1 - 8/200))
// and a 30 mm tail, in evaluation lengths of 0.5 m = 5 segments: [0, 0.5) with segments 1, 2
// and 4 (of 0..4) spoilt by dropouts (2 of 5 valid: invalid, clause 7.10), [0.5, 1.0) with
// segment 7 spoilt (4 of 5: valid), and [1.0, 1.2) holding the last two segments (shorter: listed,
// not counted). Every number by hand.
struct EvaluationRecord {
  std::vector<double> h;
  std::vector<unsigned char> drop;
  std::vector<double> msd;  // of each segment, spoilt or not
};
EvaluationRecord evaluation_record() {
  EvaluationRecord r;
  const std::size_t seg = 200;
  for (int j = 0; j < 12; ++j) {
    const double p = 1e-3 * (1 + 0.25 * j);
    const auto s = symmetric_segment(seg, 4, p, 20);
    r.h.insert(r.h.end(), s.begin(), s.end());
    r.msd.push_back(p * (1 - 8.0 / seg));
  }
  r.h.insert(r.h.end(), 60, 9e-3);  // the tail: no segment
  r.drop.assign(r.h.size(), 0);
  for (int j : {1, 2, 4, 7})
    for (std::size_t i = 0; i < 30; ++i) r.drop[j * seg + 100 + i] = 1;  // 15 % of the segment: invalid
  return r;
}

TEST(Mpd, PerEvaluationLengthByHand) {
  const EvaluationRecord rec = evaluation_record();
  MpdOptions opt;
  opt.lowpass_wavelength = 0;
  opt.spike_alpha = 0;
  opt.evaluation_length = 0.5;
  MpdAccumulator acc;
  add_profile_segments(rec.h, rec.drop, 0.5e-3, opt, acc, 3);
  const MpdResult r = summarize(acc, opt);
  EXPECT_EQ(r.segments, 12u);
  EXPECT_EQ(r.valid_segments, 8u);
  ASSERT_EQ(r.evaluations.size(), 3u);
  const double e0 = (rec.msd[0] + rec.msd[3]) / 2;
  const double e1 = (rec.msd[5] + rec.msd[6] + rec.msd[8] + rec.msd[9]) / 4;
  const double e2 = (rec.msd[10] + rec.msd[11]) / 2;
  const struct {
    double start, length, mpd;
    std::size_t segments, valid_segments;
    bool valid, complete;
  } want[] = {{0.0, 0.5, e0, 5, 2, false, true}, {0.5, 0.5, e1, 5, 4, true, true}, {1.0, 0.2, e2, 2, 2, true, false}};
  for (std::size_t k = 0; k < 3; ++k) {
    const EvaluationMpd& e = r.evaluations[k];
    EXPECT_EQ(e.profile, 3u);
    EXPECT_NEAR(e.start, want[k].start, 1e-12) << k;
    EXPECT_NEAR(e.length, want[k].length, 1e-12) << k;
    EXPECT_NEAR(e.mpd, want[k].mpd, 1e-15) << k;
    EXPECT_EQ(e.segments, want[k].segments) << k;
    EXPECT_EQ(e.valid_segments, want[k].valid_segments) << k;
    EXPECT_EQ(e.valid, want[k].valid) << k;
    EXPECT_EQ(e.complete, want[k].complete) << k;
  }
  // Counted: the complete, valid evaluation lengths only (here the second).
  EXPECT_EQ(r.evaluations_counted, 1u);
  EXPECT_NEAR(r.evaluation_mean, e1, 1e-15);
  EXPECT_NEAR(r.evaluation_min, e1, 1e-15);
  EXPECT_NEAR(r.evaluation_max, e1, 1e-15);

  // No evaluation length on a record shorter than one, and none when switched off.
  MpdAccumulator shorter, off;
  const std::size_t n = 4 * 200;
  add_profile_segments(std::vector<double>(rec.h.begin(), rec.h.begin() + n),
                       std::vector<unsigned char>(n, 0), 0.5e-3, opt, shorter);
  EXPECT_TRUE(summarize(shorter, opt).evaluations.empty());
  MpdOptions none = opt;
  none.evaluation_length = 0;
  add_profile_segments(rec.h, rec.drop, 0.5e-3, none, off);
  EXPECT_TRUE(summarize(off, none).evaluations.empty());
  EXPECT_EQ(summarize(off, none).valid_segments, 8u);
}

// A reference plate cut at the start shifts every evaluation length's start by the plate's length
// (positions are along the record as measured).
TEST(Mpd, EvaluationLengthsStartAfterACutPlate) {
  const EvaluationRecord rec = evaluation_record();
  std::vector<double> h(120, 25e-3);  // 60 mm of plate, 25 mm above the road
  h.insert(h.end(), rec.h.begin(), rec.h.end());
  MpdOptions opt;
  opt.lowpass_wavelength = 0;
  opt.spike_alpha = 0;
  opt.evaluation_length = 0.5;
  opt.cut_plates = true;
  MpdAccumulator acc;
  add_profile_segments(h, std::vector<unsigned char>(h.size(), 0), 0.5e-3, opt, acc);
  const MpdResult r = summarize(acc, opt);
  ASSERT_GT(r.plate_start, 0.0);
  ASSERT_EQ(r.evaluations.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(r.evaluations[k].start, r.plate_start + 0.5 * double(k), 1e-12);
}

class MpdCli : public wr_test::Cli {};

// Through `wetroad analyze`: the table in --json and --out, the summary on the terminal, and a
// length that is not a whole number of segments (or negative) refused in one line.
TEST_F(MpdCli, EvaluationLengthTableInEveryOutput) {
  const EvaluationRecord rec = evaluation_record();
  HeightMap m(rec.h.size(), 1, 0.5e-3, 0.5e-3, HeightMap::Kind::profile);
  m.periodic = false;
  m.h.assign(rec.h.begin(), rec.h.end());
  write_surface_file(path("rec.h5"), m, std::nullopt, {{"command", "test"}});
  // Spot method, no filters: the mean-plane removal is a line, which slope suppression removes.
  const std::string base = "analyze " + path("rec.h5") + " --mpd-method spot --lowpass 0 --spike-alpha 0 --keep-plates";
  const wr_test::CliRun r = run(base + " --evaluation-length 0.5 --json " + path("r.json") + " --out " + path("r.h5"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("per 0.5 m evaluation length"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(path("r.json")));
  const auto& ev = j["mpd_evaluation"];
  EXPECT_EQ(ev["length"].get<double>(), 0.5);
  ASSERT_EQ(ev["table"].size(), 3u);  // no dropouts here: 5, 5 and 2 valid segments
  EXPECT_EQ(ev["counted"].get<std::size_t>(), 2u);
  const double e0 = (rec.msd[0] + rec.msd[1] + rec.msd[2] + rec.msd[3] + rec.msd[4]) / 5;
  const double e1 = (rec.msd[5] + rec.msd[6] + rec.msd[7] + rec.msd[8] + rec.msd[9]) / 5;
  EXPECT_NEAR(ev["table"][0]["mpd"].get<double>(), e0, 1e-12);
  EXPECT_NEAR(ev["table"][1]["mpd"].get<double>(), e1, 1e-12);
  EXPECT_NEAR(ev["mean"].get<double>(), (e0 + e1) / 2, 1e-12);
  EXPECT_FALSE(ev["table"][2]["complete"].get<bool>());
  {
    const hid_t f = H5Fopen(path("r.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    const hid_t d = H5Dopen2(f, "/mpd_evaluation/mpd", H5P_DEFAULT);
    ASSERT_GE(d, 0);
    std::vector<double> mpd(3);
    EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, mpd.data()), 0);
    EXPECT_NEAR(mpd[0], e0, 1e-12);
    EXPECT_NEAR(mpd[1], e1, 1e-12);
    H5Dclose(d);
    H5Fclose(f);
  }
  // The default (10 m) is longer than this 1.23 m record: an empty table.
  ASSERT_EQ(run(base + " -q --json " + path("d.json")).code, 0);
  EXPECT_TRUE(nlohmann::json::parse(slurp(path("d.json")))["mpd_evaluation"]["table"].empty());
  for (const char* bad : {"0.25", "-1", "nan"}) {
    const wr_test::CliRun b = run(base + " --evaluation-length " + bad);
    EXPECT_EQ(b.code, 2) << bad << ": " << b.err;
    EXPECT_NE(b.err.find("--evaluation-length"), std::string::npos) << b.err;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
  }
}

}  // namespace
}  // namespace wr
