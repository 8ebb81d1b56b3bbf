#include "lib/spectral/viscoelastic_sliding.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstring>
#include <deque>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "lib/core/errors.hpp"
#include "lib/core/parallel.hpp"
#include "lib/core/stagnation.hpp"

namespace wr {

using cplx = std::complex<double>;

struct ViscoelasticSliding::Impl {
  std::size_t nx = 0, ny = 0, n = 0, nxh = 0;
  // Grid arrays are unpadded (n values); the FFT works in its own padded array `buf`.
  Compound compound;
  double temperature = 20;
  SlidingOptions opt;
  double qx0 = 0, qy0 = 0;
  BigVector zo;  // m, road shifted to max 0
  BigVector hx;  // dh/dx, spectral (the Nyquist column dropped)
  BigVector p, w, t, ct, r;  // pressure, face lift C p, direction, C t, gap residual
  BigVector pressure_out, gap_out;
  std::vector<unsigned char> in_contact;
  std::vector<cplx> kernel, inverse;  // C(q) / n and 1 / (C(q) n) over the half spectrum
  std::deque<std::pair<BigVector, BigVector>> window;  // (t_j, C t_j), C t_j of unit norm on the set
  BigVector buf;
  std::unique_ptr<RealFft2d> fft;
  bool have_solution = false;
  double admit_stiffness = 0;  // Pa/m: pressure given to a point on admission, per metre of penetration

  std::size_t chunks() const { return std::clamp<std::size_t>(n >> 15, 1, 64); }
  template <class F>
  void for_each(F&& f) const {
    parallel_chunks(n, chunks(), opt.threads, [&](std::size_t, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) f(k);
    });
  }
  // Sums in chunk order: the same for any thread count.
  template <std::size_t K, class F>
  std::array<double, K> reduce(F&& f) const {
    return parallel_sums<K>(n, chunks(), opt.threads, std::forward<F>(f));
  }

  double wave_x(std::size_t i) const { return qx0 * double(i); }
  double wave_y(std::size_t j) const { return qy0 * (j <= ny / 2 ? double(j) : double(j) - double(ny)); }
  // The Nyquist column's wave travels both ways at once: it carries no direction to slide along.
  bool nyquist_column(std::size_t i) const { return nx % 2 == 0 && i == nx / 2; }

  // out = (symbol) * in, a periodic convolution; `in` and `out` unpadded, may alias.
  void convolve(const BigVector& in, const std::vector<cplx>& symbol, BigVector& out) {
    const std::size_t nxp = fft->row_stride();
    for (std::size_t j = 0; j < ny; ++j) std::memcpy(buf.data() + j * nxp, in.data() + j * nx, nx * sizeof(double));
    fft->forward();
    cplx* s = fft->spectrum();
    for (std::size_t k = 0; k < ny * nxh; ++k) s[k] *= symbol[k];
    fft->backward();
    for (std::size_t j = 0; j < ny; ++j) std::memcpy(out.data() + j * nx, buf.data() + j * nxp, nx * sizeof(double));
  }

  void build_kernel(double speed) {
    const double nu = compound.poisson, nd = double(n);
    double smin = INFINITY;
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nxh; ++i) {
        const std::size_t k = j * nxh + i;
        const double kx = wave_x(i), q = std::hypot(kx, wave_y(j));
        if (q == 0) {  // the half-space's unbounded mean mode: carried by the approach
          kernel[k] = inverse[k] = 0;
          continue;
        }
        const double omega = kx * speed;
        cplx e = compound.modulus(std::abs(omega), temperature);
        if (omega < 0) e = std::conj(e);
        if (nyquist_column(i)) e = std::abs(e);  // a standing wave: lossless, |E| stiff
        const cplx c = 2 * (1 - nu * nu) / (q * e);
        kernel[k] = c / nd;
        inverse[k] = 1.0 / (c * nd);
        smin = std::min(smin, std::abs(1.0 / c));
      }
    admit_stiffness = smin;
  }

  SlidingResult solve(double speed, double pressure);
  double last_pressure = 0;
  // <p dw/dx> = sum_q |p_q|^2 (-q_x Im C(q)) from the pressure's spectrum, each stored column but
  // q_x = 0 standing for itself and its mirror; with `bins`, also split by |q| over `edges`.
  double dissipation_spectrum(const std::vector<double>& edges, std::vector<double>* bins) {
    const std::size_t nxp = fft->row_stride();
    for (std::size_t j = 0; j < ny; ++j) std::memcpy(buf.data() + j * nxp, p.data() + j * nx, nx * sizeof(double));
    fft->forward();
    const cplx* spec = fft->spectrum();
    if (bins) bins->assign(edges.empty() ? 0 : edges.size() - 1, 0.0);
    double sum = 0;
    const double nd = double(n);
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 1; i < nxh; ++i) {
        if (nyquist_column(i)) continue;
        const std::size_t k = j * nxh + i;
        const double term = 2 * std::norm(spec[k]) / (nd * nd) * (-wave_x(i) * (kernel[k] * nd).imag());
        sum += term;
        if (bins && !edges.empty()) {
          const double q = std::hypot(wave_x(i), wave_y(j));
          const auto b = std::upper_bound(edges.begin(), edges.end(), q) - edges.begin();
          if (b >= 1 && std::size_t(b) < edges.size()) (*bins)[b - 1] += term;
        }
      }
    return sum;
  }
  void iterate(double pressure, SlidingResult& res);
  void summarise(double speed, double pressure, double d, SlidingResult& res);
};

ViscoelasticSliding::ViscoelasticSliding(const HeightMap& road, const Compound& compound, double temperature,
                                         const SlidingOptions& opt)
    : impl_(std::make_unique<Impl>()) {
  if (road.nx < 2 || road.size() == 0) throw std::invalid_argument("the road map needs at least 2 samples per row");
  if (!road.periodic) throw std::invalid_argument("steady sliding needs a periodic road map");
  if (opt.window < 1) throw std::invalid_argument("the GCR window must keep at least one direction");
  if (!(opt.tolerance > 0)) throw std::invalid_argument("the tolerance must be > 0");
  compound.log10_shift(temperature);  // InputError at or below the WLF pole
  Impl& m = *impl_;
  m.nx = road.nx;
  m.ny = road.ny;
  m.n = m.nx * m.ny;
  m.nxh = m.nx / 2 + 1;
  m.compound = compound;
  m.temperature = temperature;
  m.opt = opt;
  m.qx0 = 2 * std::numbers::pi / road.lx();
  m.qy0 = 2 * std::numbers::pi / road.ly();
  double top = -INFINITY;
  for (double v : road.h) {
    if (!std::isfinite(v)) throw std::invalid_argument("the road map has non-finite heights (fill dropouts first)");
    top = std::max(top, v);
  }
  m.buf.assign(m.ny * 2 * m.nxh, 0.0);
  m.fft = std::make_unique<RealFft2d>(m.nx, m.ny, opt.threads, m.buf.data(), opt.planning, FftInput::in_place);
  m.zo.resize(m.n);
  for (std::size_t k = 0; k < m.n; ++k) m.zo[k] = road.h[k] - top;
  // dh/dx = sum i q_x h_q e^{iq.x}
  std::vector<cplx> derivative(m.ny * m.nxh);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nxh; ++i)
      derivative[j * m.nxh + i] = m.nyquist_column(i) ? 0.0 : cplx(0, m.wave_x(i) / double(m.n));
  m.hx.resize(m.n);
  m.convolve(m.zo, derivative, m.hx);
  for (auto* v : {&m.p, &m.w, &m.t, &m.ct, &m.r, &m.pressure_out, &m.gap_out}) v->assign(m.n, 0.0);
  m.in_contact.assign(m.n, 0);
  m.kernel.resize(m.ny * m.nxh);
  m.inverse.resize(m.ny * m.nxh);
}

ViscoelasticSliding::~ViscoelasticSliding() = default;

const BigVector& ViscoelasticSliding::pressure() const { return impl_->pressure_out; }
const BigVector& ViscoelasticSliding::gap() const { return impl_->gap_out; }

std::size_t ViscoelasticSliding::memory_bytes() const {
  const Impl& m = *impl_;
  const std::size_t grids = 9 + 2 * std::size_t(m.opt.window);  // zo hx p w t ct r out x2, window
  return grids * m.n * sizeof(double) + m.buf.size() * sizeof(double) + m.n +
         2 * m.kernel.size() * sizeof(cplx);
}

SlidingResult ViscoelasticSliding::solve(double speed, double pressure) {
  if (!(speed > 0 && std::isfinite(speed))) throw std::invalid_argument("the sliding speed must be > 0 m/s");
  if (!(pressure > 0 && std::isfinite(pressure))) throw std::invalid_argument("the mean pressure must be > 0 Pa");
  return impl_->solve(speed, pressure);
}

SlidingResult ViscoelasticSliding::Impl::solve(double speed, double pressure) {
  const auto t0 = std::chrono::steady_clock::now();
  SlidingResult res;
  res.speed = speed;
  build_kernel(speed);
  // Start: the last solution rescaled to the load (a sweep moves it little), else uniform.
  const double sum_p = reduce<1>([&](std::size_t k, std::array<double, 1>& a) { a[0] += p[k]; })[0];
  if (have_solution && sum_p > 0)
    for_each([&](std::size_t k) { p[k] *= pressure * double(n) / sum_p; });
  else
    std::fill(p.begin(), p.end(), pressure);
  have_solution = true;
  window.clear();
  iterate(pressure, res);
  if (!res.converged && res.message.empty())
    res.message = "viscoelastic sliding did not converge in " + std::to_string(opt.max_iterations) +
                  " iterations (last change " + (res.history.empty() ? "-" : std::to_string(res.history.back())) + ")";
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  last_pressure = pressure;
  return res;
}

std::vector<double> ViscoelasticSliding::friction_by_wavenumber(const std::vector<double>& edges) {
  Impl& m = *impl_;
  if (m.last_pressure <= 0) throw std::logic_error("friction_by_wavenumber: no solve yet");
  std::vector<double> bins;
  m.dissipation_spectrum(edges, &bins);
  for (double& b : bins) b /= m.last_pressure;
  return bins;
}

void ViscoelasticSliding::Impl::iterate(double pressure, SlidingResult& res) {
  const double nd = double(n);
  for_each([&](std::size_t k) { in_contact[k] = p[k] > 0; });
  convolve(p, kernel, w);
  ++res.fft_pairs;
  int since_full = 0, last_admit = -1000;
  double d = 0;
  for (int it = 0; it < opt.max_iterations; ++it) {
    res.iterations = it + 1;
    // The gap's mean over the contact set is the approach; the residual is the rest of it.
    const auto gs = reduce<2>([&](std::size_t k, std::array<double, 2>& a) {
      if (in_contact[k]) {
        a[0] += w[k] - zo[k];
        a[1] += 1;
      }
    });
    const double nc = gs[1];
    if (nc == 0) throw NumericalError("", "viscoelastic sliding lost every contact point");
    d = gs[0] / nc;
    for_each([&](std::size_t k) { r[k] = in_contact[k] ? w[k] - d - zo[k] : 0.0; });
    // Direction: the preconditioned residual R C^-1 R^T r, load-neutral on the set.
    convolve(r, inverse, t);
    ++res.fft_pairs;
    const double tmean = reduce<1>([&](std::size_t k, std::array<double, 1>& a) {
      if (in_contact[k]) a[0] += t[k];
    })[0] / nc;
    for_each([&](std::size_t k) { t[k] = in_contact[k] ? t[k] - tmean : 0.0; });
    convolve(t, kernel, ct);
    ++res.fft_pairs;
    // Inner products on the contact set of the mean-free parts (the approach takes the mean).
    auto dot = [&](const BigVector& a, const BigVector& b) {
      const auto s = reduce<3>([&](std::size_t k, std::array<double, 3>& acc) {
        if (in_contact[k]) {
          acc[0] += a[k] * b[k];
          acc[1] += a[k];
          acc[2] += b[k];
        }
      });
      return s[0] - s[1] * s[2] / nc;
    };
    for (const auto& [tj, ctj] : window) {  // GCR: C t orthogonal to the kept C t_j
      const double beta = dot(ct, ctj);
      for_each([&](std::size_t k) {
        t[k] -= beta * tj[k];
        ct[k] -= beta * ctj[k];
      });
    }
    const double norm = std::sqrt(std::max(dot(ct, ct), 0.0));
    if (!(norm > 0) || !std::isfinite(norm)) {
      res.message = "viscoelastic sliding: the search direction vanished (residual " +
                    std::to_string(std::sqrt(dot(r, r) / nc)) + " m)";
      break;
    }
    for_each([&](std::size_t k) {
      t[k] /= norm;
      ct[k] /= norm;
    });
    const double alpha = dot(r, ct);
    // Step, projection onto p >= 0, admission of penetrating points.
    const bool admit = (it - last_admit) >= std::max(opt.admit_every, 1);
    if (admit) last_admit = it;
    const auto ps = reduce<5>([&](std::size_t k, std::array<double, 5>& a) {
      const double pk = p[k];
      double v = in_contact[k] ? pk - alpha * t[k] : 0.0;
      if (v < 0) {
        v = 0;
        a[1] += 1;  // left the contact
      }
      const double gk = w[k] - alpha * ct[k] - d - zo[k];
      if (v == 0 && gk < 0) {
        if (admit) {
          v = -gk * admit_stiffness;
          a[2] += 1;  // (re-)entered
        } else {
          a[3] += 1;  // penetrating, waiting
        }
      }
      a[0] += v;
      a[4] += std::abs(v - pk);
      p[k] = v;
      in_contact[k] = v > 0;
    });
    const bool changed = ps[1] > 0 || ps[2] > 0;
    const double scale = ps[0] > 0 ? pressure * nd / ps[0] : 1.0;
    if (changed || std::abs(scale - 1) > 1e-14) {
      // The set or the load changed outside the directions: recompute and restart.
      for_each([&](std::size_t k) { p[k] *= scale; });
      convolve(p, kernel, w);
      ++res.fft_pairs;
      window.clear();
      since_full = 0;
    } else {
      for_each([&](std::size_t k) { w[k] -= alpha * ct[k]; });
      window.emplace_back(t, ct);
      if (window.size() > std::size_t(opt.window)) window.pop_front();
      if (++since_full >= 25) {  // incremental updates accumulate rounding
        convolve(p, kernel, w);
        ++res.fft_pairs;
        since_full = 0;
      }
    }
    const double err = ps[0] > 0 ? (ps[4] + std::abs(scale - 1) * ps[0]) / (scale * ps[0]) : 0.0;
    res.history.push_back(err);
    if (err <= opt.tolerance && ps[3] == 0) {
      res.converged = true;
      break;
    }
    if (err <= opt.tolerance) last_admit = -1000;  // converged but for waiting points: admit them now
    if (stagnated(res.history, opt.stagnation_window)) {
      res.message = "viscoelastic sliding stagnated: the change " + std::to_string(err) + " has not halved in " +
                    std::to_string(opt.stagnation_window) + " iterations (tolerance " +
                    std::to_string(opt.tolerance) + ")";
      break;
    }
  }
  convolve(p, kernel, w);
  ++res.fft_pairs;
  summarise(res.speed, pressure, d, res);
}

void ViscoelasticSliding::Impl::summarise(double speed, double pressure, double d, SlidingResult& res) {
  // The approach that closes the contact set's mean gap.
  const auto gs = reduce<2>([&](std::size_t k, std::array<double, 2>& a) {
    if (p[k] > 0) {
      a[0] += w[k] - zo[k];
      a[1] += 1;
    }
  });
  if (gs[1] > 0) d = gs[0] / gs[1];
  const auto s = reduce<6>([&](std::size_t k, std::array<double, 6>& a) {
    const double g = gap_out[k] = w[k] - d - zo[k];
    pressure_out[k] = p[k];
    a[0] += p[k];
    a[1] += p[k] > 0;
    a[2] += g;
    a[3] += p[k] * hx[k];
    a[4] = std::max(a[4], p[k] > 0 ? std::abs(g) : 0.0);
    a[5] = std::max(a[5], p[k] > 0 ? 0.0 : -g);
  });
  res.mean_pressure = s[0] / double(n);
  res.approach = d;
  res.area_fraction = s[1] / double(n);
  res.mean_gap = s[2] / double(n);
  res.mu = s[3] / double(n) / pressure;
  res.contact_gap = s[4];
  res.max_penetration = s[5];
  const double sum = dissipation_spectrum({}, nullptr);
  res.mu_dissipation = sum / pressure;
  res.dissipation = sum * speed;
  const double scale = std::max(std::abs(res.mu), std::abs(res.mu_dissipation));
  res.identity_residual = scale > 0 ? std::abs(res.mu_dissipation - res.mu) / scale : 0.0;
}

double sinusoid_full_contact_mu(const Compound& compound, double temperature, double wavenumber, double amplitude,
                                double speed, double pressure) {
  const cplx e = compound.modulus(wavenumber * speed, temperature);
  const double nu = compound.poisson;
  return std::pow(wavenumber * amplitude, 2) * e.imag() / (4 * (1 - nu * nu) * pressure);
}

}  // namespace wr
