#include "lib/spectral/normal_contact.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "lib/core/fft.hpp"
#include "lib/core/parallel.hpp"

namespace wr {

struct SpectralNormalContact::Impl {
  std::size_t nx = 0, ny = 0, n = 0;  // n: grid points
  // Every grid array below is laid out as FFTW's in-place transforms need it (FftInput::in_place):
  // rows padded to nxp = 2 (nx/2 + 1) values, np = ny nxp in all. The passes run over the
  // padding too: it holds no pressure, is never in contact, and its obstacle lies at
  // kPadHeight, so far below that it is never penetrated whatever w holds there.
  std::size_t nxp = 0, np = 0;
  static constexpr double kPadHeight = -1e300;
  ElasticBody body;
  BigVector zo;               // m, obstacle shifted to max 0
  std::vector<double> kernel;  // C(q) / n over the half spectrum (ny x nxh): FFTW is unnormalised
  std::vector<float> inverse_kernel;  // 1 / (C(q) n); 0 for the half-space's mean mode
  // 2 MiB-aligned huge pages: fewer TLB misses in the streaming passes (20 % at 2048^2).
  BigVector p;
  BigVector pressure_out, gap_out;  // the returned pressure and gap, unpadded, double
  std::vector<unsigned char> in_contact;  // p > 0, kept beside p: a byte per point is cheap to stream
  // w = C p, z (preconditioned residual), r = C t: each transformed in place by its own FFT
  // plan on its own (page-aligned) array, so no convolution copies its input or output, and
  // no spectrum buffer beside it is streamed.
  // z is single precision: a preconditioner need only be a fixed SPD operator, and rounding
  // at 1e-7 of z (relative, so shrinking with the residual) does not change the solution, which
  // is judged on the double-precision gap; its transforms take 0.6x the time of double ones.
  BigVector w;
  BigVectorSingle z;
  std::unique_ptr<RealFft2d> fft_w;
  std::unique_ptr<RealFft2dSingle> fft_z;
  // The CG's working gap, direction t and r = C t in precision Real (SpectralOptions::precision).
  // p and w stay double, and w is recomputed from p in double at least every 25 iterations:
  // single precision only perturbs the CG's search, whose progress is judged on p.
  template <class Real>
  struct CgWork {
    BigArray<Real> g, t, r;
    std::unique_ptr<BasicRealFft2d<Real>> fft_r;  // transforms r in place (t is copied into r first)
    std::vector<Real> kernel;                     // C(q) / n, as `kernel`
  };
  CgWork<float> cg_single;
  CgWork<double> cg_double;
  FftPlanning planning = FftPlanning::measure;
  // The work arrays of precision Real, allocated (and their plan made) on first use.
  template <class Real>
  CgWork<Real>& cg_work() {
    CgWork<Real>& c = [this]() -> CgWork<Real>& {
      if constexpr (std::is_same_v<Real, float>)
        return cg_single;
      else
        return cg_double;
    }();
    if (!c.fft_r) {
      for (auto* v : {&c.g, &c.t, &c.r}) v->assign(np, Real(0));
      c.fft_r = std::make_unique<BasicRealFft2d<Real>>(nx, ny, threads, c.r.data(), planning, FftInput::in_place);
      c.kernel.assign(kernel.begin(), kernel.end());
    }
    return c;
  }
  // The iterations of solve() from the start in p, with the CG in precision Real; d is the
  // approach (updated under load control).
  template <class Real>
  void iterate(CgWork<Real>& cg, bool load_control, double target, double& d, const SpectralOptions& opt,
               SpectralNormalResult& res);
  bool have_solution = false;
  // The last two converged solutions of the same kind of control and their control values:
  // a load sweep starts each solve from their linear extrapolation (the contact grows
  // smoothly), which finds most of the new contact points before the first iteration.
  BigVector p_last, p_before;
  double c_last = 0, c_before = 0;
  int history_kind = -1, history_count = 0;  // 1: load control, 0: displacement control
  double top = 0;  // m, the original obstacle's highest point: z = 0 of the approach
  void setup(const HeightMap& obstacle, double top, const ElasticBody& b, int th, FftPlanning planning);

  // out = C * in (periodic convolution through the FFT).
  int threads = 0;

  // Parallel passes over the grid in fixed chunks: sums are combined in chunk order, so
  // results do not depend on the thread count (lib/core/parallel.hpp).
  template <class F>
  void for_each(F&& f) const {
    parallel_chunks(np, chunks(), threads, [&](std::size_t, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) f(k);
    });
  }
  template <std::size_t K, class F>
  std::array<double, K> reduce(F&& f) const {
    return parallel_sums<K>(np, chunks(), threads, std::forward<F>(f));
  }
  // One chunk per 64k points, at most 64: small grids stay on one thread.
  std::size_t chunks() const { return std::clamp<std::size_t>(np >> 16, 1, 64); }

  // The array of `f` <- (multiplier `by`) * itself, a periodic convolution.
  template <class Real>
  void convolve_in_place(BasicRealFft2d<Real>& f, const std::vector<Real>& by) {
    f.forward();
    multiply_and_invert(f, by);
  }
  // The spectrum of `f` times `by`, transformed back into its array.
  template <class Real>
  void multiply_and_invert(BasicRealFft2d<Real>& f, const std::vector<Real>& by) {
    std::complex<Real>* s = f.spectrum();
    const std::size_t m = ny * f.nxh();
    parallel_chunks(m, std::clamp<std::size_t>(m >> 16, 1, 64), threads, [&](std::size_t, std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) s[k] *= by[k];
    });
    f.backward();
  }
  void update_w() {  // w = C p
    std::memcpy(w.data(), p.data(), np * sizeof(double));
    convolve_in_place(*fft_w, kernel);
  }

  SpectralNormalResult solve(bool load_control, double target, const SpectralOptions& opt);

  // Final gap of the returned pressure, both unpadded, and the summary numbers.
  void summarise(double d, SpectralNormalResult& res) {
    update_w();
    double sum_p = 0, sum_g = 0, pen = 0, cgap = 0;
    std::size_t nc = 0;
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const std::size_t k = j * nxp + i, o = j * nx + i;
        const double gk = gap_out[o] = w[k] - d - zo[k];
        pressure_out[o] = p[k];
        sum_p += p[k];
        if (p[k] > 0) {
          ++nc;
          cgap = std::max(cgap, std::abs(gk));
        } else {
          pen = std::max(pen, -gk);
        }
        sum_g += gk;
      }
    res.mean_pressure = sum_p / double(n);
    res.approach = d;
    res.area_fraction = double(nc) / double(n);
    res.mean_gap = sum_g / double(n);
    res.max_penetration = pen;
    res.contact_gap = cgap;
  }
};

SpectralNormalContact::SpectralNormalContact(const HeightMap& obstacle, const ElasticBody& body, int threads,
                                             FftPlanning planning)
    : impl_(std::make_unique<Impl>()) {
  check_body(body);
  if (obstacle.nx < 2 || obstacle.size() == 0) throw std::invalid_argument("obstacle needs at least 2 samples per row");
  if (!obstacle.periodic) throw std::invalid_argument("the spectral model needs a periodic obstacle");
  double top = -INFINITY;
  for (double v : obstacle.h) {
    if (!std::isfinite(v)) throw std::invalid_argument("obstacle has non-finite heights (fill dropouts first)");
    top = std::max(top, v);
  }
  impl_->setup(obstacle, top, body, threads, planning);
}

void SpectralNormalContact::Impl::setup(const HeightMap& obstacle, double top_height, const ElasticBody& b, int th,
                                        FftPlanning plans) {
  nx = obstacle.nx;
  ny = obstacle.ny;
  n = nx * ny;
  nxp = 2 * (nx / 2 + 1);
  np = ny * nxp;
  body = b;
  threads = th;
  top = top_height;
  zo.assign(np, kPadHeight);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) zo[j * nxp + i] = obstacle.h[j * nx + i] - top;
  planning = plans;
  w.assign(np, 0.0);
  z.assign(np, 0.0f);
  fft_w = std::make_unique<RealFft2d>(nx, ny, threads, w.data(), planning, FftInput::in_place);
  fft_z = std::make_unique<RealFft2dSingle>(nx, ny, threads, z.data(), planning, FftInput::in_place);
  std::fill(w.begin(), w.end(), 0.0);  // measuring wrote into them
  std::fill(z.begin(), z.end(), 0.0f);
  const std::size_t nxh = fft_w->nxh();
  kernel.resize(ny * nxh);
  inverse_kernel.resize(ny * nxh);
  const double qx0 = 2 * std::numbers::pi / obstacle.lx(), qy0 = 2 * std::numbers::pi / obstacle.ly();
  for (std::size_t j = 0; j < ny; ++j) {
    const double ky = qy0 * (j <= ny / 2 ? double(j) : double(j) - double(ny));
    for (std::size_t i = 0; i < nxh; ++i) {
      const double kx = qx0 * double(i), q = std::hypot(kx, ky);
      const double c = normal_compliance(body, q);
      // The half-space's unbounded mean mode is carried by the approach instead.
      kernel[j * nxh + i] = (std::isfinite(c) ? c : 0.0) / double(n);
      inverse_kernel[j * nxh + i] = float((std::isfinite(c) ? 1 / c : 0.0) / double(n));
    }
  }
  p.assign(np, 0.0);
  for (auto* v : {&pressure_out, &gap_out}) v->assign(n, 0.0);
  in_contact.assign(np, 0);
}


SpectralNormalContact::~SpectralNormalContact() = default;

void SpectralNormalContact::set_heights(const std::vector<double>& heights) {
  Impl& m = *impl_;
  if (heights.size() != m.n) throw std::invalid_argument("set_heights: the grid changed");
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.zo[j * m.nxp + i] = heights[j * m.nx + i] - m.top;
  m.history_count = 0;  // solutions on another geometry: no extrapolation from them
}

const BigVector& SpectralNormalContact::pressure() const { return impl_->pressure_out; }
const BigVector& SpectralNormalContact::gap() const { return impl_->gap_out; }
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
  if (history_kind != int(load_control)) history_count = 0;
  if (history_count >= 2 && c_last != c_before) {
    const double f = (target - c_last) / (c_last - c_before);
    for_each([&](std::size_t k) { p[k] = std::max(0.0, p_last[k] + f * (p_last[k] - p_before[k])); });
  }
  const double sum_p = reduce<1>([&](std::size_t k, std::array<double, 1>& a) { a[0] += p[k]; })[0];
  if (load_control) {
    if (have_solution && sum_p > 0)
      for_each([&](std::size_t k) { p[k] *= target * nd / sum_p; });
    else
      for_each([&](std::size_t k) { p[k] = zo[k] == kPadHeight ? 0.0 : target; });
  } else if (!have_solution || sum_p <= 0) {
    const double c0 = body.thickness / body.p_wave_modulus();
    for_each([&](std::size_t k) { p[k] = std::max(0.0, target + zo[k]) / c0; });
  }
  have_solution = true;

  for_each([&](std::size_t k) { in_contact[k] = p[k] > 0; });
  if (opt.single_precision_cg())
    iterate(cg_work<float>(), load_control, target, d, opt, res);
  else
    iterate(cg_work<double>(), load_control, target, d, opt, res);
  if (res.converged) {
    if (history_kind != int(load_control)) history_count = 0;
    history_kind = int(load_control);
    std::swap(p_before, p_last);
    p_last = p;
    c_before = c_last;
    c_last = target;
    ++history_count;
  }
  if (!res.converged && res.message.empty())
    res.message = "spectral normal contact did not converge in " + std::to_string(opt.max_iterations) +
                  " iterations (last error " + (res.history.empty() ? "-" : std::to_string(res.history.back())) + ")";
  summarise(d, res);
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

template <class Real>
void SpectralNormalContact::Impl::iterate(CgWork<Real>& cg, bool load_control, double target, double& d,
                                          const SpectralOptions& opt, SpectralNormalResult& res) {
  const double nd = double(n);
  BigArray<Real>&gap = cg.g, &t = cg.t, &r = cg.r;
  double g_old = 1.0;
  bool restart = true;
  bool w_current = false;  // w = C p holds (updated incrementally while no point changes state)
  int since_full = 0;
  int last_admit = -1000;
  // The last step's load rescaling and step length, applied to p and w in the next
  // iteration's first pass: every pass streams several grid-sized arrays through memory, which
  // costs as much as the FFTs, so the passes are fused wherever the data flow allows.
  double scale = 1.0, tau = 0.0;
  std::fill(t.begin(), t.end(), Real(0));
  for (int it = 0; it < opt.max_iterations; ++it) {
    res.iterations = it + 1;
    // Gap; under load control its mean over the contact set is the approach. Incremental
    // updates of w accumulate rounding: it is recomputed regularly.
    const bool recompute = !w_current || since_full >= 25;
    // The load rescaling still owed by p, applied where p is next rewritten (the step's pass):
    // a pass that only rescales p would stream it twice for nothing.
    const double p_scale = scale;
    if (recompute) {
      for_each([&](std::size_t k) { w[k] = scale * p[k]; });
      convolve_in_place(*fft_w, kernel);
      ++res.fft_pairs;
      since_full = 0;
    }
    const auto gs = reduce<2>([&](std::size_t k, std::array<double, 2>& a) {
      // While no point changed state, p moved by exactly -tau t, so did w.
      if (!recompute) w[k] = scale * (w[k] - tau * r[k]);
      const double gk = w[k] - d - zo[k];
      gap[k] = Real(gk);
      if (in_contact[k]) {
        a[0] += gk;
        a[1] += 1;
      }
    });
    scale = 1.0;
    const double nc = gs[1];
    if (nc == 0) {  // displacement control below first contact: nothing carries load
      std::fill(p.begin(), p.end(), 0.0);
      res.converged = true;
      break;
    }
    // The gaps used below are g - shift (the shifted approach d + shift); g itself is not rewritten.
    const double shift = load_control ? gs[0] / nc : 0.0;
    d += shift;
    // Preconditioned residual z = R C^-1 R^T g on the contact set (Vollebregt 2014): the
    // inverse compliance is diagonal in Fourier space, exact at full contact, and removes the
    // 1/q spread of the spectrum that makes plain CG take O(sqrt(N)) iterations per decade.
    for_each([&](std::size_t k) { z[k] = in_contact[k] ? float(gap[k] - shift) : 0.0f; });
    convolve_in_place(*fft_z, inverse_kernel);
    ++res.fft_pairs;
    // The sum of z over the contact set and g.z; load control then shifts z to a zero sum (a
    // load-neutral direction): g.(z - zshift) = g.z, since g - shift sums to 0 there.
    const auto zs = reduce<2>([&](std::size_t k, std::array<double, 2>& a) {
      if (in_contact[k]) {
        a[0] += z[k];
        a[1] += (gap[k] - shift) * z[k];
      }
    });
    const double zshift = load_control ? zs[0] / nc : 0.0;
    const double gz = zs[1];
    const double beta = restart ? 0.0 : gz / g_old;
    g_old = gz;
    // t is written into r's array too, which the transform in place then overwrites with C t.
    for_each([&](std::size_t k) { r[k] = t[k] = in_contact[k] ? Real((z[k] - zshift) + beta * t[k]) : Real(0); });
    convolve_in_place(*cg.fft_r, cg.kernel);  // r = C t
    ++res.fft_pairs;
    // r is shifted to a zero mean over the contact set under load control (the approach
    // absorbs the mean): (r - rshift).t = r.t - rshift sum t, and (g - shift).t likewise.
    const auto rs = reduce<4>([&](std::size_t k, std::array<double, 4>& a) {
      if (in_contact[k]) {
        a[0] += r[k];
        a[1] += gap[k] * t[k];
        a[2] += r[k] * t[k];
        a[3] += t[k];
      }
    });
    const double rshift = load_control ? rs[0] / nc : 0.0;
    const double rt = rs[2] - rshift * rs[3];
    tau = rt > 0 ? (rs[1] - shift * rs[3]) / rt : 0.0;
    // Step, projection onto p >= 0, re-admission of penetrating points (restarting CG).
    // Penetrating points join at most every `admit_every` iterations: each admission restarts
    // CG (Polonsky-Keer), and admitting at every iteration (their original scheme) keeps it
    // in steepest descent while the contact boundary settles (2x the iterations on 1024^2).
    const bool admit = (it - last_admit) >= std::max(opt.admit_every, 1);
    if (admit) last_admit = it;
    const auto ps = reduce<5>([&](std::size_t k, std::array<double, 5>& a) {
      const double gk = gap[k] - shift, pk = p_scale * p[k];
      double v = in_contact[k] ? pk - tau * t[k] : 0.0;
      if (v < 0) {
        v = 0;
        a[1] += 1;  // a point left the contact
      }
      if (v == 0 && gk < 0) {
        if (admit) {
          v = -tau * gk;
          a[2] += 1;  // a point (re-)entered
        } else {
          a[3] += 1;  // penetrating, waiting for the next admission
        }
      }
      a[0] += v;
      a[4] += std::abs(v - pk);
      p[k] = v;
      in_contact[k] = v > 0;
    });
    const bool changed = ps[1] > 0 || ps[2] > 0;
    restart = ps[2] > 0;  // Polonsky-Keer: conjugacy is lost when points enter
    double total = ps[0];
    scale = load_control && total > 0 ? target * nd / total : 1.0;
    w_current = !changed;
    if (w_current) ++since_full;
    // The error is the relative l1 change sum |scale v - p_old| / sum scale v, bounded above by
    // (sum |v - p_old| + |scale - 1| sum v) / (scale sum v): the scaling is applied later.
    const double err = total > 0 ? (ps[4] + std::abs(scale - 1) * total) / (scale * total) : 0.0;
    res.history.push_back(err);
    if (err <= opt.tolerance && ps[3] == 0) {
      res.converged = true;
      break;
    }
    if (err <= opt.tolerance) last_admit = -1000;  // converged but for waiting points: admit them now
    if (stagnated(res.history, opt.stagnation_window)) {
      res.message = "spectral normal contact stagnated: the error " + std::to_string(err) + " has not halved in " +
                    std::to_string(opt.stagnation_window) + " iterations (tolerance " + std::to_string(opt.tolerance) + ")";
      break;
    }
  }
  if (scale != 1.0) for_each([&](std::size_t k) { p[k] *= scale; });
}

}  // namespace wr
