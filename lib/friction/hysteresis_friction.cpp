#include "lib/friction/hysteresis_friction.hpp"

#include <algorithm>
#include <optional>
#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"
#include "lib/core/parallel.hpp"
#include "lib/friction/flash_temperature.hpp"

namespace wr {
namespace {

// Nodes uniform in ln q on each segment between breakpoints (the tabulated nodes and the measured
// band's end, so neither a kink of the table nor the extension's change of law falls inside an
// interval); at least two intervals per segment.
struct LogGrid {
  std::vector<double> q;             // nodes
  std::vector<std::size_t> seg_end;  // index of each segment's last node
  std::vector<double> seg_h;         // ln-q step of each segment
  std::size_t measured_end = 0;      // node at q_measured (or the last node)
};

LogGrid make_grid(const RoughnessSpectrum& psd, int per_decade) {
  // Breakpoints: every tabulated node (C is a power law between them, so the integrands are
  // smooth on each segment), the end of the measured band, and q1.
  std::vector<double> breaks = {psd.q_start};
  for (double x : psd.q)
    if (x > breaks.back() * (1 + 1e-9) && x < std::min(psd.q_measured, psd.q_end) * (1 - 1e-9)) breaks.push_back(x);
  if (psd.extrapolated() && psd.q_measured > breaks.back()) breaks.push_back(psd.q_measured);
  if (psd.q_end > breaks.back()) breaks.push_back(psd.q_end);
  LogGrid g;
  g.q.push_back(psd.q_start);
  for (std::size_t b = 1; b < breaks.size(); ++b) {
    const double a = std::log(breaks[b - 1]), z = std::log(breaks[b]);
    const int n = std::max(2, static_cast<int>(std::ceil(per_decade * (z - a) / std::log(10.0))));
    const double h = (z - a) / n;
    for (int k = 1; k <= n; ++k) g.q.push_back(k == n ? breaks[b] : std::exp(a + k * h));
    g.seg_end.push_back(g.q.size() - 1);
    g.seg_h.push_back(h);
  }
  g.measured_end = psd.extrapolated() && g.seg_end.size() >= 2 ? g.seg_end[g.seg_end.size() - 2] : g.q.size() - 1;
  return g;
}

// F[k] = int_{s_0}^{s_k} f ds: on each interval the quadratic through it and its next (or, at a
// segment's end, previous) neighbour node, h (5 f0 + 8 f1 - f2) / 12.
void cumulative(const LogGrid& g, const std::vector<double>& f, std::vector<double>& F) {
  F.assign(f.size(), 0.0);
  std::size_t begin = 0;
  for (std::size_t s = 0; s < g.seg_end.size(); ++s) {
    const std::size_t end = g.seg_end[s];
    const double h = g.seg_h[s];
    for (std::size_t k = begin; k < end; ++k) {
      const double step = k + 2 <= end ? h * (5 * f[k] + 8 * f[k + 1] - f[k + 2]) / 12
                                       : h * (-f[k - 1] + 8 * f[k] + 5 * f[k + 1]) / 12;
      F[k + 1] = F[k] + step;
    }
    begin = end;
  }
}

constexpr int kMaxFlashPasses = 400;


}  // namespace

AngleIntegrals angle_integrals(const Compound& c, double omega, double shift) {
  const std::size_t n = c.terms.size();
  // a_i r_i / (1 + sqrt(1 + a_i^2)) = (1 - r_i) / a_i without the cancellation at small a.
  double a[64], r[64];
  std::vector<double> a_big, r_big;
  double* pa = a;
  double* pr = r;
  if (n > 64) {
    a_big.resize(n);
    r_big.resize(n);
    pa = a_big.data();
    pr = r_big.data();
  }
  const double eg = c.glassy_modulus();
  double loss = 0, single = 0;
  for (std::size_t i = 0; i < n; ++i) {
    pa[i] = omega * c.terms[i].tau * shift;
    const double root = std::sqrt(1 + pa[i] * pa[i]);
    pr[i] = 1 / root;
    loss += c.terms[i].de * pa[i] * pr[i] / (1 + root);
    single += c.terms[i].de * pr[i];
  }
  double pair = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double row = 0;
    for (std::size_t j = 0; j < n; ++j) row += c.terms[j].de / (pa[i] + pa[j]);
    pair += c.terms[i].de * pa[i] * pr[i] * row;
  }
  AngleIntegrals out;
  out.loss = 2 * M_PI * loss;
  // Eg^2 - 2 Eg sum dE r + 2 sum dE dE a r/(a+a'): at low frequency the terms cancel to Er^2;
  // the floor keeps the (exact) lower bound Er^2 against round-off.
  out.power = std::max(2 * M_PI * (eg * eg - 2 * eg * single + 2 * pair), 2 * M_PI * c.e_relaxed * c.e_relaxed);
  return out;
}

void check_friction_options(const FrictionOptions& opt, const Compound& compound) {
  if (!(opt.pressure > 0 && std::isfinite(opt.pressure)))
    throw InputError("--pressure", "the nominal pressure must be a positive number of Pa, got " + number_text(opt.pressure));
  if (opt.points_per_decade < 4 || opt.points_per_decade > 10000)
    throw InputError("--points-per-decade", "must lie in 4 ... 10000");
  // A tread on a road, flash temperature included, stays far inside this range; the compound's
  // WLF shift is fitted nearer still, and beyond it exp() of the shift overflows.
  if (!(opt.temperature >= -100 && opt.temperature <= 300))
    throw InputError("--temperature", "must be a temperature in -100 ... 300 deg C, got " + number_text(opt.temperature));
  compound.log10_shift(opt.temperature);  // throws at the WLF pole
}

FrictionPoint hysteresis_friction(const RoughnessSpectrum& psd, const Compound& compound, double v,
                                  const FrictionOptions& opt) {
  if (!(v > 0 && std::isfinite(v))) throw InputError("--speeds", "a sliding speed must be positive, got " + number_text(v));
  const LogGrid g = make_grid(psd, opt.points_per_decade);
  const std::size_t n = g.q.size();
  const double e0 = (1 - compound.poisson * compound.poisson) * opt.pressure;
  std::vector<double> temp(n, opt.temperature), gG(n), gM(n), G, F, P(n), f(n);
  std::vector<double> c_at(n);
  for (std::size_t k = 0; k < n; ++k) c_at[k] = psd(g.q[k]);
  std::optional<FlashTemperature> flash;
  if (opt.flash_temperature) flash.emplace(compound, v, opt.pressure);
  std::vector<double> rise(n), R;
  for (int pass = 0;; ++pass) {
    for (std::size_t k = 0; k < n; ++k) {
      const double q = g.q[k];
      const double shift = std::pow(10.0, compound.log10_shift(temp[k]));
      const AngleIntegrals a = angle_integrals(compound, q * v, shift);
      const double q4c = q * q * q * q * c_at[k];  // dq = q d(ln q)
      gG[k] = q4c * a.power / (8 * e0 * e0);
      gM[k] = 0.5 * q4c * a.loss / e0;
    }
    cumulative(g, gG, G);
    for (std::size_t k = 0; k < n; ++k) {
      P[k] = G[k] > 0 ? std::erf(1 / (2 * std::sqrt(G[k]))) : 1.0;
      f[k] = gM[k] * P[k];
    }
    cumulative(g, f, F);
    if (!flash) break;
    // T_q = T0 + the rise of every coarser scale (flash_temperature.hpp); damped fixed point.
    for (std::size_t k = 0; k < n; ++k) rise[k] = flash->rise_density(g.q[k], gM[k]);
    cumulative(g, rise, R);
    double change = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double target = opt.temperature + std::max(0.0, R[k]);
      change = std::max(change, std::abs(target - temp[k]));
      temp[k] += 0.5 * (target - temp[k]);
    }
    if (change < 1e-3) break;
    if (pass >= kMaxFlashPasses)
      throw NumericalError("--flash-temperature", "the flash temperature did not settle at v = " + number_text(v) +
                                                      " m/s (last change " + number_text(change) + " K)");
  }
  FrictionPoint out;
  out.v = v;
  out.mu = F.back();
  out.area_fraction = P.back();
  out.temperature_rise = temp.back() - opt.temperature;
  out.mu_extrapolated = F.back() - F[g.measured_end];
  if (!std::isfinite(out.mu) || !std::isfinite(out.area_fraction))
    throw NumericalError("", "non-finite friction at v = " + number_text(v) + " m/s");
  return out;
}

std::vector<FrictionPoint> friction_curve(const RoughnessSpectrum& psd, const Compound& compound,
                                          const std::vector<double>& speeds, const FrictionOptions& opt) {
  std::vector<FrictionPoint> out(speeds.size());
  parallel_chunks(speeds.size(), speeds.size(), opt.threads, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) out[i] = hysteresis_friction(psd, compound, speeds[i], opt);
  });
  return out;
}

}  // namespace wr
