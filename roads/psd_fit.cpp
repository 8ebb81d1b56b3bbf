#include "roads/psd_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lib/core/least_squares.hpp"

namespace wr {
namespace {

struct Line {
  double a = 0, beta = 0, sse = 0;
};

// Weighted least squares of y = a - beta * max(0, x - x0) (rows scaled by sqrt(w)).
Line fit_for_knee(const std::vector<double>& x, const std::vector<double>& y,
                  const std::vector<double>& w, double x0) {
  const Eigen::Index n = Eigen::Index(x.size());
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double sw = std::sqrt(w[std::size_t(i)]);
    A(i, 0) = sw;
    A(i, 1) = -sw * std::max(0.0, x[std::size_t(i)] - x0);
    b(i) = sw * y[std::size_t(i)];
  }
  Line L;
  if (const auto c = least_squares(A, b)) {
    L.a = (*c)(0);
    L.beta = (*c)(1);
  } else {  // no bin beyond the knee: a level line
    double sy = 0, sw = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sy += w[i] * y[i], sw += w[i];
    L.a = sy / sw;
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - (L.a - L.beta * std::max(0.0, x[i] - x0));
    L.sse += w[i] * r * r;
  }
  return L;
}

}  // namespace

PsdFit fit_self_affine(const RadialPsd& psd, double nyquist, bool profile) {
  PsdFit f;
  double peak = 0;
  for (double c : psd.C) peak = std::max(peak, c);
  std::vector<double> x, y, w;
  std::size_t cut = psd.q.size();
  for (std::size_t i = 0; i < psd.q.size(); ++i)
    if (psd.C[i] <= 1e-8 * peak) {
      cut = i;
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
  double best_x0 = x.front();
  Line best = fit_for_knee(x, y, w, best_x0);
  for (std::size_t i = 1; i + 2 < x.size(); ++i) {
    const Line L = fit_for_knee(x, y, w, x[i]);
    if (L.sse < best.sse) {
      best = L;
      best_x0 = x[i];
    }
  }
  double lo = std::max(x.front(), best_x0 - 0.5 * (x[1] - x[0]) - 0.7);
  double hi = std::min(x[x.size() - 3], best_x0 + 0.7);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
  for (int it = 0; it < 60 && hi - lo > 1e-7; ++it) {
    if (fit_for_knee(x, y, w, c).sse < fit_for_knee(x, y, w, d).sse)
      hi = d;
    else
      lo = c;
    c = hi - g * (hi - lo);
    d = lo + g * (hi - lo);
  }
  const double x0 = 0.5 * (lo + hi);
  const Line refined = fit_for_knee(x, y, w, x0);
  if (refined.sse < best.sse) {
    best = refined;
    best_x0 = x0;
  }

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
