#include "roads/profile_filters.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wr {

bool interpolate_invalid(double* h, const unsigned char* invalid, std::size_t n) {
  std::size_t first = n;
  for (std::size_t i = 0; i < n; ++i)
    if (!invalid[i]) {
      first = i;
      break;
    }
  if (first == n) return false;
  for (std::size_t i = 0; i < first; ++i) h[i] = h[first];
  std::size_t prev = first;
  for (std::size_t i = first + 1; i < n; ++i) {
    if (invalid[i]) continue;
    for (std::size_t j = prev + 1; j < i; ++j) {
      const double t = double(j - prev) / double(i - prev);
      h[j] = (1 - t) * h[prev] + t * h[i];
    }
    prev = i;
  }
  for (std::size_t j = prev + 1; j < n; ++j) h[j] = h[prev];
  return true;
}

std::size_t mark_spikes(const double* h, unsigned char* invalid, std::size_t n, double threshold) {
  if (n < 3) return 0;
  if (threshold <= 0) {
    double s = 0;
    for (std::size_t i = 1; i < n; ++i) s += (h[i] - h[i - 1]) * (h[i] - h[i - 1]);
    threshold = 6.0 * std::sqrt(s / double(n - 1));
    if (!(threshold > 0)) return 0;
  }
  std::size_t count = 0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (invalid[i]) continue;
    const double a = h[i] - h[i - 1], b = h[i] - h[i + 1];
    if ((a > threshold && b > threshold) || (a < -threshold && b < -threshold)) {
      invalid[i] = 1;
      ++count;
    }
  }
  return count;
}

namespace {

struct Biquad {
  double b0, b1, b2, a1, a2;
};

Biquad butterworth2(double dx, double cutoff_wavelength) {
  const double k = std::tan(std::numbers::pi * dx / cutoff_wavelength);  // tan(pi fc / fs)
  const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k * k);
  Biquad f;
  f.b0 = k * k * norm;
  f.b1 = 2 * f.b0;
  f.b2 = f.b0;
  f.a1 = 2 * (k * k - 1) * norm;
  f.a2 = (1 - std::sqrt(2.0) * k + k * k) * norm;
  return f;
}

// Direct form II transposed, started in the steady state of input x[0] (unit DC gain).
void run(const Biquad& f, std::vector<double>& x) {
  double z1 = (1 - f.b0) * x[0], z2 = (f.b2 - f.a2) * x[0];
  for (double& v : x) {
    const double in = v;
    const double y = f.b0 * in + z1;
    z1 = f.b1 * in - f.a1 * y + z2;
    z2 = f.b2 * in - f.a2 * y;
    v = y;
  }
}

}  // namespace

bool lowpass_zero_phase(double* h, std::size_t n, double dx, double cutoff_wavelength) {
  if (n < 2 || !(cutoff_wavelength > 0)) return false;
  if (dx / cutoff_wavelength > 0.45) return false;  // fc above 0.9 Nyquist
  const Biquad f = butterworth2(dx, cutoff_wavelength);
  // Transients of a 2nd-order Butterworth die out within a few cut-off wavelengths.
  const std::size_t pad = std::min<std::size_t>(n - 1, static_cast<std::size_t>(std::ceil(4 * cutoff_wavelength / dx)));
  std::vector<double> x(n + 2 * pad);
  for (std::size_t i = 0; i < pad; ++i) {
    x[i] = 2 * h[0] - h[pad - i];
    x[pad + n + i] = 2 * h[n - 1] - h[n - 2 - i];
  }
  std::copy(h, h + n, x.begin() + pad);
  run(f, x);
  std::reverse(x.begin(), x.end());
  run(f, x);
  std::reverse(x.begin(), x.end());
  std::copy(x.begin() + pad, x.begin() + pad + n, h);
  return true;
}

}  // namespace wr
