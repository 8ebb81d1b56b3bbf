#include "lib/friction/squeeze_out.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wr {
namespace {

constexpr int kNodesPerPhase = 400;
constexpr double kFreePressure = 1e-9;   // p_c / sigma0 below which the asperities carry nothing
constexpr double kEquilibrium = 1e-9;    // (sigma0 - p_c) / sigma0 where the history stops
constexpr double kSmoothDepth = 1e-3;    // without asperities: follow u down to u0 * this

}  // namespace

double smooth_plates_squeeze_time(double eta, double L, double sigma0, double u0, double u) {
  return eta * L * L / (2 * sigma0) * (1 / (u * u) - 1 / (u0 * u0));
}

SqueezeHistory::SqueezeHistory(const SqueezeLaw& law, const SqueezeSetup& s) : pressure_(s.pressure) {
  if (!(s.pressure > 0 && s.viscosity > 0 && s.drainage_length > 0 && s.initial_separation > 0))
    throw std::invalid_argument("SqueezeHistory: pressure, viscosity, drainage length and film must be > 0");
  const double sigma0 = s.pressure, c = s.viscosity * s.drainage_length * s.drainage_length / 12;
  const double p_free = kFreePressure * sigma0;
  const double u_free = law.separation(p_free);  // 0 for smooth plates
  const double u0 = s.initial_separation;
  double t = 0;
  // dt per unit of the integration variable at a node, the node's state.
  struct Node {
    double rate;
    SqueezeState st;
  };
  auto add = [&](const Node& prev, const Node& next, double dvar) {
    t += 0.5 * (prev.rate + next.rate) * dvar;
    SqueezeState st = next.st;
    st.t = t;
    nodes_.push_back(st);
  };
  // Phase 1: the film alone carries the load: dt/d(ln u) = c u / (K(u, 0) sigma0).
  auto film_node = [&](double u) {
    const double K = law.conductance(u, 0.0);
    return Node{K > 0 ? c * u / (K * sigma0) : std::numeric_limits<double>::infinity(), {0, u, 0, 0}};
  };
  double p_start = p_free;
  if (u0 > u_free) {
    const double u_end = u_free > 0 ? u_free : u0 * kSmoothDepth;
    const double a = std::log(u0), b = std::log(u_end), h = (b - a) / kNodesPerPhase;
    Node prev = film_node(u0);
    nodes_.push_back(prev.st);
    for (int k = 1; k <= kNodesPerPhase && std::isfinite(prev.rate); ++k) {
      const Node next = film_node(std::exp(a + k * h));
      if (!std::isfinite(next.rate)) {
        trapped_ = true;
        break;
      }
      add(prev, next, -h);
      prev = next;
    }
    if (u_free <= 0) trapped_ = false;
  } else {
    // The asperities already carry part of the load when the tread meets this film.
    double lo = std::log(p_free), hi = std::log(sigma0);
    for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
      const double mid = 0.5 * (lo + hi);
      (law.separation(std::exp(mid)) > u0 ? lo : hi) = mid;
    }
    p_start = std::exp(0.5 * (lo + hi));
    nodes_.push_back({0, u0, p_start, law.contact(p_start)});
  }
  // Phase 2: over the asperity pressure p: dt/dp = c (-du/dp) / (K (sigma0 - p)).
  if (u_free > 0 && !trapped_ && p_start < sigma0 * (1 - kEquilibrium)) {
    auto rate_dp = [&](double p) {
      const double e = 1e-4, u = law.separation(p), A = law.contact(p);
      const double dudp = (law.separation(p * (1 + e)) - law.separation(p * (1 - e))) / (2 * e * p);
      const double K = law.conductance(u, A);
      const double r = K > 0 ? c * (-dudp) / (K * (sigma0 - p)) : std::numeric_limits<double>::infinity();
      return Node{r, {0, u, p, A}};
    };
    // Integration variable: ln p up to sigma0/2, then -ln(sigma0 - p); dp/dvar = p or (sigma0 - p).
    std::vector<double> ps;
    const double half = 0.5 * sigma0;
    if (p_start < half)
      for (int k = 0; k <= kNodesPerPhase; ++k) ps.push_back(p_start * std::pow(half / p_start, double(k) / kNodesPerPhase));
    const double g0 = sigma0 - std::max(half, p_start), g1 = kEquilibrium * sigma0;
    for (int k = ps.empty() ? 0 : 1; k <= kNodesPerPhase; ++k) ps.push_back(sigma0 - g0 * std::pow(g1 / g0, double(k) / kNodesPerPhase));
    Node prev = rate_dp(ps[0]);
    for (std::size_t k = 1; k < ps.size(); ++k) {
      const Node next = rate_dp(ps[k]);
      if (!std::isfinite(next.rate)) {
        trapped_ = true;
        break;
      }
      // The interval's variable: ln p below sigma0/2, -ln(sigma0 - p) above; trapezoid in it of
      // (dt/dp)(dp/dvar) at both ends.
      const bool log_p = ps[k] <= half * (1 + 1e-12);
      auto jacobian = [&](double p) { return log_p ? p : sigma0 - p; };
      const double dvar = log_p ? std::log(ps[k] / ps[k - 1]) : std::log((sigma0 - ps[k - 1]) / (sigma0 - ps[k]));
      Node a = prev, b = next;
      a.rate *= jacobian(ps[k - 1]);
      b.rate *= jacobian(ps[k]);
      add(a, b, dvar);
      prev = next;
    }
  }
  // Running integrals of the load share and of (1 - A)/u over t.
  share_.resize(nodes_.size());
  film_.resize(nodes_.size());
  share_int_.assign(nodes_.size(), 0.0);
  film_int_.assign(nodes_.size(), 0.0);
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    share_[k] = nodes_[k].asperity_pressure / sigma0;
    film_[k] = (1 - nodes_[k].contact) / nodes_[k].separation;
    if (k > 0) {
      const double dt = nodes_[k].t - nodes_[k - 1].t;
      share_int_[k] = share_int_[k - 1] + 0.5 * dt * (share_[k] + share_[k - 1]);
      film_int_[k] = film_int_[k - 1] + 0.5 * dt * (film_[k] + film_[k - 1]);
    }
  }
}

SqueezeState SqueezeHistory::at(double t) const {
  if (t <= 0 || nodes_.size() == 1) return nodes_.front();
  if (t >= nodes_.back().t) return nodes_.back();
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t, [](double x, const SqueezeState& s) { return x < s.t; });
  const SqueezeState &b = *it, &a = *(it - 1);
  const double r = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
  return {t, a.separation + r * (b.separation - a.separation), a.asperity_pressure + r * (b.asperity_pressure - a.asperity_pressure),
          a.contact + r * (b.contact - a.contact)};
}

double SqueezeHistory::cumulative(const std::vector<double>& integral, const std::vector<double>& value, double T) const {
  if (T >= nodes_.back().t) return integral.back() + (T - nodes_.back().t) * value.back();
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), T, [](double x, const SqueezeState& s) { return x < s.t; });
  const std::size_t k = static_cast<std::size_t>(it - nodes_.begin());  // nodes_[k-1].t <= T < nodes_[k].t
  const double dt = T - nodes_[k - 1].t, span = nodes_[k].t - nodes_[k - 1].t;
  const double vT = value[k - 1] + (span > 0 ? dt / span : 0) * (value[k] - value[k - 1]);
  return integral[k - 1] + 0.5 * dt * (value[k - 1] + vT);
}

double SqueezeHistory::mean_load_share(double T) const { return cumulative(share_int_, share_, T) / T; }
double SqueezeHistory::mean_inverse_film(double T) const { return cumulative(film_int_, film_, T) / T; }

double SqueezeHistory::time_to_share(double share) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    if (share_[k] >= share) {
      if (k == 0) return 0.0;
      const double r = (share - share_[k - 1]) / (share_[k] - share_[k - 1]);
      return nodes_[k - 1].t + r * (nodes_[k].t - nodes_[k - 1].t);
    }
  return std::numeric_limits<double>::infinity();
}

}  // namespace wr
