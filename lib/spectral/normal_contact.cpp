#include "lib/spectral/normal_contact.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include "lib/core/fft.hpp"

namespace wr {

struct SpectralNormalContact::Impl {
  std::size_t nx = 0, ny = 0, n = 0;
  ElasticBody body;
  std::vector<double> zo;      // m, obstacle shifted to max 0
  std::vector<double> kernel;  // C(q) / n over the half spectrum (ny x nxh): FFTW is unnormalised
  std::unique_ptr<RealFft2d> fft;
  std::vector<double> p, g, t, w, r, p_prev;
  bool have_solution = false;

  // out = C * in (periodic convolution through the FFT).
  void apply(const std::vector<double>& in, std::vector<double>& out) {
    std::memcpy(fft->real(), in.data(), n * sizeof(double));
    fft->forward();
    std::complex<double>* s = fft->spectrum();
    const std::size_t m = ny * fft->nxh();
    for (std::size_t k = 0; k < m; ++k) s[k] *= kernel[k];
    fft->backward();
    std::memcpy(out.data(), fft->real(), n * sizeof(double));
  }

  SpectralNormalResult solve(bool load_control, double target, const SpectralOptions& opt);

  // Final gap of the returned pressure and the summary numbers.
  void summarise(bool load_control, double d, SpectralNormalResult& res) {
    apply(p, w);
    double sum_p = 0, sum_g = 0, pen = 0, cgap = 0;
    std::size_t nc = 0;
    for (std::size_t k = 0; k < n; ++k) {
      g[k] = w[k] - d - zo[k];
      sum_p += p[k];
      if (p[k] > 0) {
        ++nc;
        cgap = std::max(cgap, std::abs(g[k]));
      } else {
        pen = std::max(pen, -g[k]);
      }
      sum_g += g[k];
    }
    (void)load_control;
    res.mean_pressure = sum_p / double(n);
    res.approach = d;
    res.area_fraction = double(nc) / double(n);
    res.mean_gap = sum_g / double(n);
    res.max_penetration = pen;
    res.contact_gap = cgap;
  }
};

SpectralNormalContact::SpectralNormalContact(const HeightMap& obstacle, const ElasticBody& body, int threads)
    : impl_(std::make_unique<Impl>()) {
  check_body(body);
  if (obstacle.nx < 2 || obstacle.size() == 0) throw std::invalid_argument("obstacle needs at least 2 samples per row");
  if (!obstacle.periodic) throw std::invalid_argument("the spectral model needs a periodic obstacle");
  Impl& m = *impl_;
  m.nx = obstacle.nx;
  m.ny = obstacle.ny;
  m.n = m.nx * m.ny;
  m.body = body;
  m.zo.assign(obstacle.h.begin(), obstacle.h.end());
  double top = -INFINITY;
  for (double v : m.zo) {
    if (!std::isfinite(v)) throw std::invalid_argument("obstacle has non-finite heights (fill dropouts first)");
    top = std::max(top, v);
  }
  for (double& v : m.zo) v -= top;
  m.fft = std::make_unique<RealFft2d>(m.nx, m.ny, threads);
  const std::size_t nxh = m.fft->nxh();
  m.kernel.resize(m.ny * nxh);
  const double qx0 = 2 * std::numbers::pi / obstacle.lx(), qy0 = 2 * std::numbers::pi / obstacle.ly();
  for (std::size_t j = 0; j < m.ny; ++j) {
    const double ky = qy0 * (j <= m.ny / 2 ? double(j) : double(j) - double(m.ny));
    for (std::size_t i = 0; i < nxh; ++i) {
      const double kx = qx0 * double(i), q = std::hypot(kx, ky);
      const double c = normal_compliance(body, q);
      // The half-space's unbounded mean mode is carried by the approach instead.
      m.kernel[j * nxh + i] = (std::isfinite(c) ? c : 0.0) / double(m.n);
    }
  }
  m.p.assign(m.n, 0.0);
  m.g.assign(m.n, 0.0);
  m.t.assign(m.n, 0.0);
  m.w.assign(m.n, 0.0);
  m.r.assign(m.n, 0.0);
  m.p_prev.assign(m.n, 0.0);
}

SpectralNormalContact::~SpectralNormalContact() = default;

const std::vector<double>& SpectralNormalContact::pressure() const { return impl_->p; }
const std::vector<double>& SpectralNormalContact::gap() const { return impl_->g; }
std::size_t SpectralNormalContact::nx() const { return impl_->nx; }
std::size_t SpectralNormalContact::ny() const { return impl_->ny; }

SpectralNormalResult SpectralNormalContact::solve_load(double mean_pressure, const SpectralOptions& opt) {
  if (!(mean_pressure > 0)) throw std::invalid_argument("the mean pressure must be > 0");
  return impl_->solve(true, mean_pressure, opt);
}

SpectralNormalResult SpectralNormalContact::solve_approach(double approach, const SpectralOptions& opt) {
  if (impl_->body.half_space())
    throw std::invalid_argument("displacement control needs a layer of finite thickness (the half-space's mean "
                                "compliance is unbounded); give a load instead");
  if (!(approach >= 0)) throw std::invalid_argument("the approach must be >= 0");
  return impl_->solve(false, approach, opt);
}

SpectralNormalResult SpectralNormalContact::Impl::solve(bool load_control, double target, const SpectralOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  SpectralNormalResult res;
  const double nd = double(n);
  double d = load_control ? 0.0 : target;  // the approach (found by load control)

  // Start: the previous solution (rescaled to the new load) or, cold, a uniform pressure
  // (load control) / the local uniaxial estimate of a Winkler bed (displacement control).
  double sum_p = 0;
  for (double v : p) sum_p += v;
  if (load_control) {
    if (have_solution && sum_p > 0)
      for (double& v : p) v *= target * nd / sum_p;
    else
      std::fill(p.begin(), p.end(), target);
  } else if (!have_solution || sum_p <= 0) {
    const double c0 = body.thickness / body.p_wave_modulus();
    for (std::size_t k = 0; k < n; ++k) p[k] = std::max(0.0, target + zo[k]) / c0;
  }
  have_solution = true;

  double g_old = 1.0;
  bool restart = true;
  std::fill(t.begin(), t.end(), 0.0);
  for (int it = 0; it < opt.max_iterations; ++it) {
    res.iterations = it + 1;
    apply(p, w);
    // Gap; under load control its mean over the contact set is the approach.
    std::size_t nc = 0;
    double gsum = 0;
    for (std::size_t k = 0; k < n; ++k) {
      g[k] = w[k] - d - zo[k];
      if (p[k] > 0) {
        gsum += g[k];
        ++nc;
      }
    }
    if (nc == 0) {  // displacement control below first contact: nothing carries load
      std::fill(p.begin(), p.end(), 0.0);
      res.converged = true;
      break;
    }
    if (load_control) {
      const double shift = gsum / double(nc);
      d += shift;
      for (double& v : g) v -= shift;
    }
    double gg = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (p[k] > 0) gg += g[k] * g[k];
    const double beta = restart ? 0.0 : gg / g_old;
    g_old = gg;
    for (std::size_t k = 0; k < n; ++k) t[k] = p[k] > 0 ? g[k] + beta * t[k] : 0.0;
    apply(t, r);
    if (load_control) {
      double rsum = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (p[k] > 0) rsum += r[k];
      rsum /= double(nc);
      for (double& v : r) v -= rsum;
    }
    double gt = 0, rt = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (p[k] > 0) {
        gt += g[k] * t[k];
        rt += r[k] * t[k];
      }
    const double tau = rt > 0 ? gt / rt : 0.0;
    // Step, projection onto p >= 0, re-admission of penetrating points (restarting CG).
    restart = false;
    for (std::size_t k = 0; k < n; ++k) {
      p_prev[k] = p[k];
      double v = p[k] > 0 ? p[k] - tau * t[k] : 0.0;
      if (v < 0) v = 0;
      if (v == 0 && g[k] < 0) {
        v = -tau * g[k];
        restart = true;
      }
      p[k] = v;
    }
    double total = 0;
    for (double v : p) total += v;
    if (load_control && total > 0) {
      for (double& v : p) v *= target * nd / total;
      total = target * nd;
    }
    double change = 0;
    for (std::size_t k = 0; k < n; ++k) change += std::abs(p[k] - p_prev[k]);
    const double err = total > 0 ? change / total : 0.0;
    res.history.push_back(err);
    if (err <= opt.tolerance) {
      res.converged = true;
      break;
    }
  }
  if (!res.converged)
    res.message = "spectral normal contact did not converge in " + std::to_string(opt.max_iterations) +
                  " iterations (last error " + (res.history.empty() ? "-" : std::to_string(res.history.back())) + ")";
  summarise(load_control, d, res);
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace wr
