// Spectrum and moments against exact answers: sinusoids and Parseval.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "lib/core/big_buffer.hpp"
#include "lib/core/fft.hpp"
#include "roads/height_stats.hpp"
#include "roads/spectrum.hpp"

namespace wr {
namespace {

constexpr double kPi = std::numbers::pi;

// a sin(kx x + ky y) on an n x n periodic grid of period L, with kx = 2 pi mx / L etc.
HeightMap sinusoid(std::size_t n, double L, double a, int mx, int my) {
  HeightMap m(n, n, L / n, L / n);
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix)
      m(ix, iy) = a * std::sin(2 * kPi * (mx * double(ix) + my * double(iy)) / double(n));
  return m;
}

// Bar 4: PSD peak at the right q; h0 = a / sqrt 2 and rms slope (2 pi a / lambda) / sqrt 2 to 1e-10.
TEST(Spectrum, SinusoidAlongX) {
  const double L = 0.03, a = 2e-4;
  const int m = 7;
  const HeightMap h = sinusoid(256, L, a, m, 0);
  const double lambda = L / m, q = 2 * kPi / lambda;
  const SpectrumResult s = analyze_spectrum(h);
  EXPECT_NEAR(std::sqrt(s.moments.m0) / (a / std::sqrt(2.0)), 1.0, 1e-10);
  EXPECT_NEAR(height_stats(h).sq / (a / std::sqrt(2.0)), 1.0, 1e-10);
  EXPECT_NEAR(std::sqrt(2 * s.moments.m2) / (2 * kPi * a / lambda / std::sqrt(2.0)), 1.0, 1e-10);
  const auto peak = std::max_element(s.psd.C.begin(), s.psd.C.end()) - s.psd.C.begin();
  EXPECT_NEAR(s.psd.q[peak] / q, 1.0, 1e-12);
  // All the power sits in that bin: bin mean times count times the cell equals h0^2.
  const double qL = 2 * kPi / L;
  EXPECT_NEAR(s.psd.C[peak] * s.psd.count[peak] * qL * qL / (a * a / 2), 1.0, 1e-10);
}

TEST(Spectrum, OblongSinusoidGivesIsotropicMoments) {
  // A wave along (3, 4): |q| = 5 qL; rms gradient = |q| a / sqrt 2 in any direction.
  const double L = 0.02, a = 1e-4;
  const HeightMap h = sinusoid(128, L, a, 3, 4);
  const double q = 5 * 2 * kPi / L;
  const SpectrumResult s = analyze_spectrum(h);
  EXPECT_NEAR(std::sqrt(2 * s.moments.m2) / (q * a / std::sqrt(2.0)), 1.0, 1e-10);
  // m4 of the isotropic formula: 3/8 |B|^2 q^4 summed over +-q = (3/8) (a^2/2) q^4.
  EXPECT_NEAR(s.moments.m4 / (0.375 * a * a / 2 * std::pow(q, 4)), 1.0, 1e-10);
}

TEST(Spectrum, NyquistSinusoidIsCountedOnce) {
  // cos(pi n) on an even grid: the self-conjugate Nyquist coefficient.
  const std::size_t n = 64;
  HeightMap h(n, n, 1e-4, 1e-4);
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) h(ix, iy) = (ix % 2 ? -1.0 : 1.0) * 1e-5;
  const SpectrumResult s = analyze_spectrum(h);
  EXPECT_NEAR(s.moments.m0 / 1e-10, 1.0, 1e-12);
}

TEST(Spectrum, ParsevalOnRandomMap) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0, 1e-4);
  HeightMap h(90, 70, 1e-4, 2e-4);
  for (double& v : h.h) v = g(rng);
  double mean = 0;
  for (double v : h.h) mean += v;
  mean /= h.h.size();
  for (double& v : h.h) v -= mean;
  const SpectrumResult s = analyze_spectrum(h);
  EXPECT_NEAR(std::sqrt(s.moments.m0) / height_stats(h).sq, 1.0, 1e-12);
}

TEST(Spectrum, ProfileMomentsAreTheSurfaceMoments) {
  // A profile through an isotropic surface: m2 = <h'^2>, m4 = <h''^2> (eq. 3.14-3.17).
  const std::size_t n = 512;
  const double L = 0.05, a = 3e-4;
  HeightMap p(n, 1, L / n, L / n, HeightMap::Kind::profile);
  const int m = 11;
  for (std::size_t i = 0; i < n; ++i) p.h[i] = a * std::cos(2 * kPi * m * double(i) / n);
  const double q = 2 * kPi * m / L;
  const SpectrumResult s = analyze_spectrum(p);
  EXPECT_NEAR(s.moments.m0 / (a * a / 2), 1.0, 1e-10);
  EXPECT_NEAR(s.moments.m2 / (a * a / 2 * q * q), 1.0, 1e-10);
  EXPECT_NEAR(s.moments.m4 / (a * a / 2 * q * q * q * q), 1.0, 1e-10);
}

TEST(HeightStats, FiniteDifferenceSlopeOfSinusoidMatchesTheDiscreteFormula) {
  // Forward differences of a sin(q x) have rms (2 a / dx) sin(q dx / 2) / sqrt 2.
  const double L = 0.03, a = 2e-4;
  const std::size_t n = 300;
  const HeightMap h = sinusoid(n, L, a, 9, 0);
  const double q = 2 * kPi * 9 / L, dx = L / n;
  EXPECT_NEAR(rms_slope_finite_difference(h) / (2 * a / dx * std::sin(q * dx / 2) / std::sqrt(2.0)), 1.0, 1e-10);
}

TEST(HeightStats, CentralDifferenceSlopeOfSinusoidMatchesTheDiscreteFormula) {
  // Central differences of a sin(q x) have rms (a / dx) sin(q dx) / sqrt 2, on the periodic map
  // and on its non-periodic copy (interior differences only: still exact to rounding for a
  // whole number of periods, since sin^2 averages over the 300 - 2 centres to within 1/n).
  const double L = 0.03, a = 2e-4;
  const std::size_t n = 300;
  HeightMap h = sinusoid(n, L, a, 0, 23);  // along y: the other axis than the forward test
  const double q = 2 * kPi * 23 / L, dx = L / n, expect = a / dx * std::sin(q * dx) / std::sqrt(2.0);
  EXPECT_NEAR(rms_slope_finite_difference(h, 0, SlopeStencil::central) / expect, 1.0, 1e-10);
  h.periodic = false;
  EXPECT_NEAR(rms_slope_finite_difference(h, 0, SlopeStencil::central) / expect, 1.0, 2.0 / double(n));
  // The stencil damps short waves: at 23 waves over 300 cells the central slope is
  // cos(q dx / 2) times the forward one.
  h.periodic = true;
  EXPECT_NEAR(rms_slope_finite_difference(h, 0, SlopeStencil::central) / rms_slope_finite_difference(h),
              std::cos(q * dx / 2), 1e-10);
}

TEST(HeightStats, SkewnessAndKurtosisOfASinusoid) {
  const HeightMap h = sinusoid(200, 0.02, 1e-4, 4, 0);
  const HeightStats s = height_stats(h);
  EXPECT_NEAR(s.ssk, 0.0, 1e-10);
  EXPECT_NEAR(s.sku, 1.5, 1e-10);  // <sin^4> / <sin^2>^2 = (3/8) / (1/4)
  // Sa of the sampled wave: mean |sin| over the 50 samples of a period (2/pi in the limit).
  double mean_abs = 0;
  for (int i = 0; i < 50; ++i) mean_abs += std::abs(std::sin(2 * kPi * i / 50.0)) / 50;
  EXPECT_NEAR(s.sa / (1e-4 * mean_abs), 1.0, 1e-12);
  EXPECT_NEAR(mean_abs, 2 / kPi, 2e-3);
}


// Measured plans compute the same transform as estimated ones (to rounding), are stored in the
// wisdom file, and a transform from an external array equals one from the plan's own array.
TEST(Fft, MeasuredPlansAgreeAndAreCached) {
  const std::string wisdom = ::testing::TempDir() + "wetroad-test-wisdom";
  std::remove(wisdom.c_str());
  ::setenv("WETROAD_FFT_WISDOM", wisdom.c_str(), 1);
  const std::size_t nx = 96, ny = 80;  // a size no other test plans
  RealFft2d est(nx, ny, 1, nullptr, FftPlanning::estimate), mea(nx, ny, 1, nullptr, FftPlanning::measure);
  ::unsetenv("WETROAD_FFT_WISDOM");
  std::ifstream cached(wisdom);
  std::stringstream text;
  text << cached.rdbuf();
  EXPECT_NE(text.str().find("fftw"), std::string::npos) << "no wisdom written to " << wisdom;
  BigVector x(nx * ny);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = std::sin(0.37 * double(k)) + 0.1 * double(k % 7);
  std::copy(x.begin(), x.end(), est.real());
  est.forward();
  mea.forward_from(x.data());
  double worst = 0, peak = 0;
  for (std::size_t k = 0; k < ny * est.nxh(); ++k) {
    worst = std::max(worst, std::abs(est.spectrum()[k] - mea.spectrum()[k]));
    peak = std::max(peak, std::abs(est.spectrum()[k]));
  }
  EXPECT_LT(worst, 1e-12 * peak);
  EXPECT_EQ(x[5], std::sin(0.37 * 5) + 0.1 * 5);  // the external input is left intact
  mea.backward();
  for (std::size_t k = 0; k < x.size(); k += 97) EXPECT_NEAR(mea.real()[k] / double(nx * ny), x[k], 1e-12);
  std::remove(wisdom.c_str());
}


// The single-precision transform (the spectral solver's preconditioner) matches the double one to
// float rounding (the error of an FFT grows like eps log N: 1e-5 of the peak is ample for 7680
// points with eps = 6e-8), keeps its measured plans in their own wisdom file, and round-trips.
TEST(Fft, SinglePrecisionMatchesDoubleToFloatRounding) {
  const std::string wisdom = ::testing::TempDir() + "wetroad-test-wisdom-sp";
  std::remove(wisdom.c_str());
  std::remove((wisdom + "-single").c_str());
  ::setenv("WETROAD_FFT_WISDOM", wisdom.c_str(), 1);
  const std::size_t nx = 96, ny = 80;
  RealFft2d d(nx, ny, 1, nullptr, FftPlanning::estimate);
  RealFft2dSingle f(nx, ny, 1, nullptr, FftPlanning::measure);
  ::unsetenv("WETROAD_FFT_WISDOM");
  std::ifstream cached(wisdom + "-single");
  std::stringstream text;
  text << cached.rdbuf();
  EXPECT_NE(text.str().find("fftwf"), std::string::npos) << "no single-precision wisdom in " << wisdom << "-single";
  for (std::size_t k = 0; k < nx * ny; ++k) {
    const double v = std::sin(0.37 * double(k)) + 0.1 * double(k % 7);
    d.real()[k] = v;
    f.real()[k] = float(v);
  }
  d.forward();
  f.forward();
  double worst = 0, peak = 0;
  for (std::size_t k = 0; k < ny * d.nxh(); ++k) {
    const std::complex<double> fk(f.spectrum()[k].real(), f.spectrum()[k].imag());
    worst = std::max(worst, std::abs(d.spectrum()[k] - fk));
    peak = std::max(peak, std::abs(d.spectrum()[k]));
  }
  EXPECT_LT(worst, 1e-5 * peak);
  EXPECT_GT(worst, 0.0);  // it really is single precision
  f.backward();
  for (std::size_t k = 0; k < nx * ny; k += 97)
    EXPECT_NEAR(f.real()[k] / double(nx * ny), std::sin(0.37 * double(k)) + 0.1 * double(k % 7), 1e-5);
  std::remove(wisdom.c_str());
  std::remove((wisdom + "-single").c_str());
}

// A plan allowed to destroy its input transforms as a preserving one (to rounding), and
// forward_from() on it never writes into the caller's array.
TEST(Fft, DestroyingPlansTransformAlikeAndSpareForeignInput) {
  const std::size_t nx = 64, ny = 48, n = nx * ny;
  RealFft2d keep(nx, ny, 1, nullptr, FftPlanning::estimate);
  RealFft2d lose(nx, ny, 1, nullptr, FftPlanning::estimate, FftInput::destroy);
  std::vector<double> in(n);
  for (std::size_t k = 0; k < n; ++k) in[k] = std::cos(0.21 * double(k)) + 0.05 * double(k % 11);
  std::copy(in.begin(), in.end(), keep.real());
  keep.forward();
  EXPECT_TRUE(std::equal(in.begin(), in.end(), keep.real()));  // the preserving plan kept it
  const std::vector<double> foreign = in;
  lose.forward_from(foreign.data());
  EXPECT_EQ(foreign, in);
  double worst = 0, peak = 0;
  for (std::size_t k = 0; k < ny * keep.nxh(); ++k) {
    worst = std::max(worst, std::abs(keep.spectrum()[k] - lose.spectrum()[k]));
    peak = std::max(peak, std::abs(keep.spectrum()[k]));
  }
  EXPECT_LT(worst, 1e-12 * peak);
  lose.backward();
  for (std::size_t k = 0; k < n; ++k) ASSERT_NEAR(lose.real()[k] / double(n), in[k], 1e-12);
}

// An in-place plan reads and writes rows padded to row_stride() = 2 (nx/2 + 1) and gives the
// transform of a separate-buffer plan (to rounding), odd row length included.
TEST(Fft, InPlacePlansUsePaddedRowsAndTransformAlike) {
  for (std::size_t nx : {64u, 45u}) {
    const std::size_t ny = 36, n = nx * ny;
    RealFft2d ref(nx, ny, 1, nullptr, FftPlanning::estimate);
    RealFft2d in_place(nx, ny, 1, nullptr, FftPlanning::estimate, FftInput::in_place);
    const std::size_t stride = in_place.row_stride();
    EXPECT_EQ(stride, 2 * (nx / 2 + 1));
    EXPECT_EQ(ref.row_stride(), nx);
    EXPECT_EQ(static_cast<void*>(in_place.spectrum()), static_cast<void*>(in_place.real()));
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        ref.real()[j * nx + i] = in_place.real()[j * stride + i] = std::sin(0.13 * double(i) + 0.7 * double(j)) + 0.1 * double((i * j) % 5);
    ref.forward();
    in_place.forward();
    double worst = 0, peak = 0;
    for (std::size_t k = 0; k < ny * ref.nxh(); ++k) {
      worst = std::max(worst, std::abs(ref.spectrum()[k] - in_place.spectrum()[k]));
      peak = std::max(peak, std::abs(ref.spectrum()[k]));
    }
    EXPECT_LT(worst, 1e-12 * peak) << "nx " << nx;
    in_place.backward();
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        ASSERT_NEAR(in_place.real()[j * stride + i] / double(n), ref.real()[j * nx + i], 1e-12) << "nx " << nx;
  }
}

}  // namespace
}  // namespace wr
