#include "roads/expected_mpd.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "lib/core/fft.hpp"

namespace wr {
namespace {

// 16-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr double kGlX[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                            0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
constexpr double kGlW[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                            0.1246289712555339, 0.0951585116824928, 0.0622535239424102, 0.0271524594117541};

template <class F>
double gauss16(F f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double s = 0;
  for (int i = 0; i < 8; ++i) s += kGlW[i] * (f(c - h * kGlX[i]) + f(c + h * kGlX[i]));
  return s * h;
}

}  // namespace

double profile_psd(const SelfAffinePsd& psd, double qx) {
  qx = std::abs(qx);
  if (qx > psd.q1_cut) return 0.0;
  // Plateau extended to q = 0 (see header): use a copy with qL -> 0.
  SelfAffinePsd ext = psd;
  ext.qL = 0;
  auto C = [&](double qy) { return ext(std::sqrt(qx * qx + qy * qy)); };
  const double qy_max = std::sqrt(psd.q1_cut * psd.q1_cut - qx * qx);
  // Split at the roll-off kink (qy where |q| = q0) and grade the power-law tail geometrically.
  double s = 0, a = 0;
  if (qx < psd.q0) {
    const double knee = std::sqrt(psd.q0 * psd.q0 - qx * qx);
    s += gauss16(C, 0, std::min(knee, qy_max));
    a = knee;
  }
  if (qy_max > a) {
    double lo = a, hi = std::max(a, std::max(qx, psd.q0) * 0.25);
    if (hi <= lo) hi = lo + 0.25 * std::max(qx, psd.q0);
    while (lo < qy_max) {
      hi = std::min(hi, qy_max);
      s += gauss16(C, lo, hi);
      lo = hi;
      hi = lo * 2;
    }
  }
  return 2 * s;
}

ExpectedMpd expected_mpd(const SelfAffinePsd& psd, double surface_dx, const ExpectedMpdOptions& opt) {
  ExpectedMpd r;
  const double dx = std::max(surface_dx, opt.min_spacing);
  std::size_t n = static_cast<std::size_t>(std::ceil(opt.length / dx));
  n += n % 2;
  r.spacing = dx;
  const double qL = 2 * std::numbers::pi / (n * dx);
  const std::size_t nh = n / 2 + 1;

  // C1 on a log grid of wavenumbers, interpolated in log-log (it is smooth except at the cut).
  const double q_top = std::min(psd.q1_cut, std::numbers::pi / dx);
  const int grid = 256;
  std::vector<double> lq(grid), lc(grid);
  for (int i = 0; i < grid; ++i) {
    const double q = qL * std::pow(q_top / qL, double(i) / (grid - 1));
    lq[i] = std::log(q);
    lc[i] = std::log(std::max(profile_psd(psd, q), 1e-300));
  }
  auto c1 = [&](double q) {
    if (q > q_top) return 0.0;
    const double x = std::log(q);
    const double t = (x - lq[0]) / (lq[1] - lq[0]);
    const int i = std::clamp(static_cast<int>(t), 0, grid - 2);
    const double f = t - i;
    return std::exp((1 - f) * lc[i] + f * lc[i + 1]);
  };

  RealFft2d fft(n, 1, 1);
  std::mt19937_64 rng(opt.seed);
  MpdAccumulator acc;
  std::vector<unsigned char> none(n, 0);
  for (int p = 0; p < opt.profiles; ++p) {
    auto* X = fft.spectrum();
    X[0] = 0;
    for (std::size_t k = 1; k < nh; ++k) {
      const double phase = 2 * std::numbers::pi * static_cast<double>(rng() >> 11) * 0x1.0p-53;
      const double amp = std::sqrt(c1(k * qL) * qL);  // |B_q|^2 = C1 qL
      X[k] = (k == n / 2) ? std::complex<double>(amp * std::cos(phase), 0) : std::polar(amp, phase);
    }
    fft.backward();
    add_profile_segments(std::vector<double>(fft.real(), fft.real() + n), none, dx, opt.mpd, acc);
  }
  const MpdResult m = summarize(acc, opt.mpd);
  r.mpd = m.mpd;
  r.mpd_std = m.mpd_std;
  r.segments = m.valid_segments;
  r.std_error = m.valid_segments > 1 ? m.mpd_std / std::sqrt(double(m.valid_segments)) : NAN;
  r.assumption = "PSD plateau extended to q = 0 (no texture beyond the sample's roll-off); " +
                 std::to_string(opt.profiles) + " random-phase profiles of " +
                 std::to_string(static_cast<int>(opt.length * 1000)) + " mm";
  return r;
}

}  // namespace wr
