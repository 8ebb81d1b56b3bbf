#include "lib/friction/roughness_spectrum.hpp"

#include <algorithm>
#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"

namespace wr {
namespace {

struct Nodes {
  std::vector<double> q, C;
};

// The radial PSD's bins (count > 0, 0 < q <= nyquist, C > 0) averaged over cells of
// 1/kLogBinsPerDecade decade in ln q, each bin weighted by its coefficient count: C at the
// count-weighted geometric mean q of the cell. The linear bins crowd at high q, where their
// scatter is estimator noise; the average keeps the power (sum of count x C) of every cell.
Nodes measured_nodes(const RadialPsd& psd, double nyquist) {
  Nodes n;
  double cell = -1, wsum = 0, lq = 0, csum = 0;
  auto flush = [&] {
    if (wsum > 0) {
      n.q.push_back(std::exp(lq / wsum));
      n.C.push_back(csum / wsum);
    }
    wsum = lq = csum = 0;
  };
  for (std::size_t i = 0; i < psd.q.size(); ++i) {
    if (!(psd.count[i] > 0 && psd.q[i] > 0 && psd.q[i] <= nyquist * (1 + 1e-12) && psd.C[i] > 0 &&
          std::isfinite(psd.C[i])))
      continue;
    const double c = std::floor(std::log10(psd.q[i]) * kLogBinsPerDecade);
    if (c != cell) {
      flush();
      cell = c;
    }
    wsum += psd.count[i];
    lq += psd.count[i] * std::log(psd.q[i]);
    csum += psd.count[i] * psd.C[i];
  }
  flush();
  return n;
}


}  // namespace

double RoughnessSpectrum::operator()(double x) const {
  if (q.empty() || x < q_start * (1 - 1e-12) || x > q_end * (1 + 1e-12)) return 0;
  if (x > q_measured) return scale * extension_scale * extension_anchor * std::pow(x / q_measured, -extension_beta);
  if (x <= q.front()) return scale * C.front();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(q.begin(), q.end(), x) - q.begin());
  if (i >= q.size()) return scale * C.back();
  const double t = std::log(x / q[i - 1]) / std::log(q[i] / q[i - 1]);
  return scale * std::exp((1 - t) * std::log(C[i - 1]) + t * std::log(C[i]));
}

double RoughnessSpectrum::rms_height() const {
  const int n = 4000;
  const double a = std::log(q_start), b = std::log(q_end), h = (b - a) / n;
  double sum = 0;
  for (int k = 0; k <= n; ++k) {
    const double x = std::exp(a + k * h);
    sum += (k == 0 || k == n ? 0.5 : 1.0) * x * x * (*this)(x);
  }
  return std::sqrt(2 * M_PI * sum * h);
}

RoughnessSpectrum spectrum_from_psd(const RadialPsd& psd, double nyquist, const PsdFit& fit,
                                    std::optional<double> q1, const std::string& source) {
  Nodes n = measured_nodes(psd, nyquist);
  if (n.q.size() < 3) throw InputError(source, "the surface resolves fewer than 3 wavenumbers: no spectrum to slide on");
  RoughnessSpectrum s;
  s.q = std::move(n.q);
  s.C = std::move(n.C);
  s.q_start = s.q.front();
  s.q_measured = s.q.back();
  s.q_end = q1 ? *q1 : std::max(kDefaultQ1, s.q_measured);
  if (!std::isfinite(s.q_end) || s.q_end <= s.q[1])
    throw InputError("--q1", number_text(s.q_end) + " 1/m lies below the measured band of " + source + " (" +
                                 number_text(s.q[1]) + " ... " + number_text(s.q_measured) + " 1/m)");
  if (s.extrapolated()) {
    if (!fit.ok || !(fit.beta > 0))
      throw InputError(source, "q1 = " + number_text(s.q_end) + " 1/m lies above the measured band (" +
                                   number_text(s.q_measured) + " 1/m) and the self-affine fit failed (" + fit.note +
                                   "): give --q1 <= " + number_text(s.q_measured));
    s.extension_beta = fit.beta;
    s.extension_anchor = s.q_measured <= fit.q0 ? fit.plateau_k
                                                : fit.plateau_k * std::pow(s.q_measured / fit.q0, -fit.beta);
  } else {
    // Cut inside the measured band: the last node is the one at or below q1 (interpolated there).
    while (s.q.size() > 2 && s.q[s.q.size() - 2] >= s.q_end) {
      s.q.pop_back();
      s.C.pop_back();
    }
    s.q_measured = s.q_end;
  }
  return s;
}

RoughnessSpectrum wet_spectrum(const RoughnessSpectrum& dry, const RadialPsd& wet_psd, double nyquist,
                               double extension_scale) {
  Nodes n = measured_nodes(wet_psd, nyquist);
  RoughnessSpectrum s = dry;
  s.q.clear();
  s.C.clear();
  // Same nodes as the dry surface (same grid): keep those the wet surface still has power at.
  for (std::size_t i = 0; i < n.q.size(); ++i)
    if (n.q[i] <= dry.q.back() * (1 + 1e-12)) {
      s.q.push_back(n.q[i]);
      s.C.push_back(n.C[i]);
    }
  if (s.q.size() < 2) throw InputError("", "the wet surface is flat: no spectrum to slide on");
  s.extension_scale = extension_scale;
  return s;
}

RoughnessSpectrum band_spectrum(double qa, double qb, double c) {
  RoughnessSpectrum s;
  s.q = {qa, qb};
  s.C = {c, c};
  s.q_start = qa;
  s.q_end = qb;
  s.q_measured = qb;
  return s;
}

double q1_for_rms_slope(const RadialPsd& psd, double nyquist, const PsdFit& fit, double slope, const std::string& source,
                        const std::string& option) {
  if (!(slope > 0 && std::isfinite(slope))) throw InputError(option, "the rms slope of the criterion must be > 0");
  constexpr double kCap = 1e9;  // 1/m: a nanometre; no road's criterion lies beyond
  const RoughnessSpectrum full = spectrum_from_psd(psd, nyquist, fit, kCap, source);
  // 2 pi int q^3 C dq in ln q (integrand 2 pi q^4 C), trapezoid on 200 nodes per decade
  const double a = std::log(full.q_start), b = std::log(kCap);
  const int n = static_cast<int>(std::ceil((b - a) / std::log(10.0) * 200));
  const double h = (b - a) / n, target = slope * slope;
  double sum = 0, prev = 2 * M_PI * std::pow(full.q_start, 4) * full(full.q_start);
  for (int k = 1; k <= n; ++k) {
    const double q = std::exp(a + k * h), f = 2 * M_PI * std::pow(q, 4) * full(q), step = 0.5 * h * (prev + f);
    if (sum + step >= target) {
      const double t = step > 0 ? (target - sum) / step : 1.0;  // linear within the last interval
      return std::exp(a + (k - 1 + t) * h);
    }
    sum += step;
    prev = f;
  }
  throw InputError(option, "the surface's rms slope reaches only " + std::to_string(std::sqrt(sum)) + " by q = 1e9 1/m, not " +
                               std::to_string(slope));
}

}  // namespace wr
