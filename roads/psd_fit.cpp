#include "roads/psd_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace wr {
namespace {

struct Line {
  double a = 0, beta = 0, sse = 0;
};

// Weighted least squares of y = a - beta * max(0, x - x0) (x ascending) for any knee x0 in O(log n).
//
// A full refit per candidate knee costs O(n), and the scan visits every bin: O(n^2) in the
// profile's length (issue 54: 200k samples took 87 s). For fixed x0 the fit only needs the
// weighted sums of 1, u = max(0, x - x0), u^2, y, u y, y^2; the sums over the bins beyond the
// knee are kept per bin k as suffix sums of powers of (x_i - x_k), anchored at x_k itself, so that
// with d = x_k - x0 > 0
//   sum u = A1 + d W,  sum u^2 = A2 + 2 d A1 + d^2 W,  sum u y = B + d Y
// adds nonnegative terms only (no cancellation between large sums, unlike expanding around a
// global origin). y is centred on its weighted mean first. The normal equations of the two
// unknowns then give the fit and its residual sum of squares exactly as the QR refit did, to
// rounding (tests/test_spectrum.cpp compares the two on 2048 bins).
class KneeFitter {
 public:
  KneeFitter(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& w)
      : x_(x), n_(x.size()), W_(n_ + 1, 0.0), Y_(n_ + 1, 0.0), A1_(n_ + 1, 0.0), A2_(n_ + 1, 0.0), B_(n_ + 1, 0.0) {
    double sw = 0, swy = 0;
    for (std::size_t i = 0; i < n_; ++i) sw += w[i], swy += w[i] * y[i];
    ybar_ = swy / sw;
    S0_ = sw;
    for (std::size_t i = 0; i < n_; ++i) {
      const double yc = y[i] - ybar_;
      Sy_ += w[i] * yc;
      Syy_ += w[i] * yc * yc;
    }
    for (std::size_t k = n_; k-- > 0;) {
      const double yc = y[k] - ybar_;
      const double d = k + 1 < n_ ? x[k + 1] - x[k] : 0.0;  // shift of the anchor from x_{k+1} to x_k
      W_[k] = W_[k + 1] + w[k];
      Y_[k] = Y_[k + 1] + w[k] * yc;
      A1_[k] = A1_[k + 1] + d * W_[k + 1];
      A2_[k] = A2_[k + 1] + 2 * d * A1_[k + 1] + d * d * W_[k + 1];
      B_[k] = B_[k + 1] + d * Y_[k + 1];
    }
  }

  double total_sse() const { return Syy_ - Sy_ * Sy_ / S0_; }  // about the weighted mean

  Line fit(double x0) const {
    // The bins beyond the knee: x_i > x0 (a bin at the knee itself has u = 0).
    const std::size_t k = std::size_t(std::upper_bound(x_.begin(), x_.end(), x0) - x_.begin());
    const double syy_c = Syy_ - Sy_ * Sy_ / S0_;
    Line L;
    if (k < n_) {
      const double d = x_[k] - x0;
      const double su = A1_[k] + d * W_[k];
      const double suu = A2_[k] + 2 * d * A1_[k] + d * d * W_[k];
      const double suy = B_[k] + d * Y_[k];
      const double suu_c = suu - su * su / S0_, suy_c = suy - su * Sy_ / S0_;
      if (suu_c > 1e-14 * suu) {
        const double slope = suy_c / suu_c;  // of y against u: -beta
        L.beta = -slope;
        L.a = ybar_ + (Sy_ - slope * su) / S0_;
        L.sse = std::max(0.0, syy_c - slope * suy_c);
        return L;
      }
    }
    // No bin beyond the knee: a level line.
    L.a = ybar_ + Sy_ / S0_;
    L.sse = std::max(0.0, syy_c);
    return L;
  }

 private:
  const std::vector<double>& x_;
  std::size_t n_;
  double ybar_ = 0, S0_ = 0, Sy_ = 0, Syy_ = 0;
  // Suffix sums over bins i >= k: sum w, sum w (y - ybar), sum w (x_i - x_k), sum w (x_i - x_k)^2,
  // sum w (x_i - x_k)(y_i - ybar).
  std::vector<double> W_, Y_, A1_, A2_, B_;
};

// The residual sum of squares of a line, summed bin by bin (for the figures reported).
double residual_sse(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& w,
                    const Line& L, double x0) {
  double sse = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - (L.a - L.beta * std::max(0.0, x[i] - x0));
    sse += w[i] * r * r;
  }
  return sse;
}

}  // namespace

PsdFit fit_self_affine(const RadialPsd& psd, double nyquist, bool profile) {
  PsdFit f;
  double peak = 0;
  for (double c : psd.C) peak = std::max(peak, c);
  std::vector<double> x, y, w;
  // The cut-off is where the spectrum falls below 1e-8 of its peak and stays there (a synthesized
  // surface's q1). Not at the first bin below it: a measured profile's periodogram scatters bin by
  // bin (exponentially, chi-square with 2 degrees of freedom), and over the millions of bins of a
  // long record some bin dips that low at random, which cut the fit at a random wavenumber.
  std::size_t cut = 0;
  for (std::size_t i = psd.q.size(); i-- > 0;)
    if (psd.C[i] > 1e-8 * peak) {
      cut = i + 1;
      break;
    }
  // The bin just below a hard cut-off is only partly filled: leave it out too.
  const std::size_t last = cut < psd.q.size() && cut > 0 ? cut - 1 : cut;
  for (std::size_t i = 0; i < last; ++i) {
    if (psd.q[i] > nyquist * (1 + 1e-9) || !(psd.C[i] > 0)) continue;
    x.push_back(std::log(psd.q[i]));
    y.push_back(std::log(psd.C[i]));
    w.push_back(psd.count[i]);
  }
  if (x.size() < 4) {
    f.note = "fewer than 4 usable PSD bins";
    return f;
  }
  f.bins = x.size();
  f.q_min = std::exp(x.front());
  f.q_max = std::exp(x.back());

  // Scan the knee over the bin positions (the first bin means "no plateau"), then refine.
  const KneeFitter fitter(x, y, w);
  double best_x0 = x.front();
  Line best = fitter.fit(best_x0);
  for (std::size_t i = 1; i + 2 < x.size(); ++i) {
    const Line L = fitter.fit(x[i]);
    if (L.sse < best.sse) {
      best = L;
      best_x0 = x[i];
    }
  }
  // The sums give the residual to about 1e-16 of the total variance: where the fit is closer
  // than 1e-8 of it (an exact synthetic spectrum), the golden section would compare rounding, so
  // there the residual is summed bin by bin (O(n), at most 121 times: still linear).
  const double close = 1e-8 * fitter.total_sse();
  const auto sse_at = [&](double x0) {
    const Line L = fitter.fit(x0);
    return L.sse < close ? residual_sse(x, y, w, L, x0) : L.sse;
  };
  double lo = std::max(x.front(), best_x0 - 0.5 * (x[1] - x[0]) - 0.7);
  double hi = std::min(x[x.size() - 3], best_x0 + 0.7);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
  for (int it = 0; it < 60 && hi - lo > 1e-7; ++it) {
    if (sse_at(c) < sse_at(d))
      hi = d;
    else
      lo = c;
    c = hi - g * (hi - lo);
    d = lo + g * (hi - lo);
  }
  const double x0 = 0.5 * (lo + hi);
  Line refined = fitter.fit(x0);
  refined.sse = sse_at(x0);
  if (refined.sse < best.sse) {
    best = refined;
    best_x0 = x0;
  }
  best.sse = residual_sse(x, y, w, best, best_x0);

  double sw = 0, sy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sw += w[i];
    sy += w[i] * y[i];
  }
  double sst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sst += w[i] * (y[i] - sy / sw) * (y[i] - sy / sw);
  f.plateau_k = std::exp(best.a);
  f.q0 = std::exp(best_x0);
  f.beta = best.beta;
  f.hurst = profile ? 0.5 * (best.beta - 1) : 0.5 * best.beta - 1;
  f.r2 = sst > 0 ? 1 - best.sse / sst : 1.0;
  f.rms_log10 = std::sqrt(best.sse / sw) / std::log(10.0);
  f.ok = true;
  if (f.q0 <= f.q_min * 1.0001) f.note = "no plateau found: q0 at the first bin";
  return f;
}

}  // namespace wr
