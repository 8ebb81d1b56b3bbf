#include "bench/bench_squeeze.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "lib/flow/contact_gap.hpp"
#include "lib/flow/effective_medium.hpp"
#include "lib/flow/thin_film_flow.hpp"
#include "lib/friction/load_separation.hpp"
#include "lib/friction/squeeze_out.hpp"
#include "lib/friction/tyre_test.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"
#include "roads/synthesize.hpp"

namespace wr::bench {
namespace {

// The map's interface: rows ascending in the asperity pressure.
struct Row {
  double p, u, a, k;
};

std::vector<Row> map_ladder(const HeightMap& map, const SqueezeBenchSetup& st) {
  SpectralNormalContact solver(map, ElasticBody{st.young, st.poisson}, st.threads, FftPlanning::estimate);
  SpectralOptions opt;
  opt.tolerance = 1e-8;
  opt.threads = st.threads;
  std::vector<Row> rows;
  for (int i = 0; i < st.ladder_points; ++i) {
    // sigma0 * 1e-4 ... 2 sigma0, log-spaced (warm starts from the lighter load)
    const double p = st.pressure * 1e-4 * std::pow(2e4, double(i) / (st.ladder_points - 1));
    const SpectralNormalResult r = solver.solve_load(p, opt);
    const HeightMap gap = contact_gap_map(map, solver.pressure(), solver.gap());
    const FlowConductance k = thin_film_conductance(gap, {});
    rows.push_back({p, r.mean_gap, r.area_fraction, 0.5 * (k.kxx + k.kyy)});
  }
  return rows;
}

// Piecewise log-linear interpolation of y against x over the rows (x ascending); `below` and
// `above` decide the values outside.
template <class X, class Y>
double interpolate(const std::vector<Row>& rows, double x, X xof, Y yof, bool log_y) {
  if (x <= xof(rows.front())) return yof(rows.front());
  if (x >= xof(rows.back())) return yof(rows.back());
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (x <= xof(rows[i])) {
      const double t = std::log(x / xof(rows[i - 1])) / std::log(xof(rows[i]) / xof(rows[i - 1]));
      const double a = yof(rows[i - 1]), b = yof(rows[i]);
      if (log_y && a > 0 && b > 0) return a * std::pow(b / a, t);
      return a + t * (b - a);
    }
  return yof(rows.back());
}

// The map's rows as a squeeze law. Below the lightest load the separated surfaces' exponential
// law continues the last two points; above the widest gap K grows as u^3 (parallel plates).
SqueezeLaw map_law(const std::vector<Row>& rows) {
  SqueezeLaw law;
  const Row &r0 = rows[0], &r1 = rows[1];
  const double decay = (r0.u - r1.u) / std::log(r1.p / r0.p);  // du / d ln(1/p)
  law.separation = [rows, r0, decay](double p) {
    if (p < r0.p) return r0.u + decay * std::log(r0.p / p);
    return interpolate(rows, p, [](const Row& r) { return r.p; }, [](const Row& r) { return r.u; }, true);
  };
  law.contact = [rows](double p) {
    return interpolate(rows, p, [](const Row& r) { return r.p; }, [](const Row& r) { return r.a; }, false);
  };
  std::vector<Row> by_gap(rows.rbegin(), rows.rend());  // ascending in u
  law.conductance = [by_gap](double u, double) {
    const Row& top = by_gap.back();
    if (u >= top.u) return top.k * std::pow(u / top.u, 3);
    if (u <= by_gap.front().u) return by_gap.front().k;
    return interpolate(by_gap, u, [](const Row& r) { return r.u; }, [](const Row& r) { return r.k; }, true);
  };
  return law;
}

nlohmann::json summary(const SqueezeHistory& h, double patch_time) {
  auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"t_first_contact", finite(h.time_to_share(0.01))},
          {"t_drained", finite(h.time_to_share(0.9))},
          {"load_share", h.mean_load_share(patch_time)},
          {"trapped", h.trapped()}};
}

}  // namespace

nlohmann::json squeeze_rungs(const SqueezeBenchSetup& st) {
  nlohmann::json out = nlohmann::json::array();
  Compound rubber;
  rubber.name = "elastic";
  rubber.e_relaxed = st.young;
  rubber.poisson = st.poisson;
  for (double h0 : st.h0) {
    SynthParams sp;
    sp.nx = sp.ny = st.n;
    sp.dx = 3e-2 / double(st.n);
    sp.h0 = h0;
    sp.hurst = 0.7;
    sp.q0_ratio = 5;
    sp.q1 = std::numbers::pi / sp.dx;
    sp.seed = st.seed;
    sp.threads = st.threads;
    const HeightMap map = synthesize(sp).map;
    // the mean field on the map's own band (no extrapolation: the map carries no finer scales)
    const SpectrumResult s = analyze_spectrum(map, st.threads);
    const PsdFit fit = fit_self_affine(s.psd, s.nyquist, false);
    const RoughnessSpectrum psd = spectrum_from_psd(s.psd, s.nyquist, fit, s.nyquist, "bench squeeze");
    const LoadSeparation ls(psd, rubber, 1.0, 20, 48);
    SqueezeLaw mean_field;
    const double rms = ls.rms_height();
    mean_field.separation = [&ls](double p) { return ls.separation(p); };
    mean_field.contact = [&ls](double p) { return ls.contact_fraction(p); };
    mean_field.conductance = [rms](double u, double a) { return effective_medium_conductance({a, u, rms}); };
    const std::vector<Row> rows = map_ladder(map, st);
    const SqueezeLaw on_map = map_law(rows);
    nlohmann::json ladder = nlohmann::json::array();
    for (const Row& r : rows)
      ladder.push_back({{"p", r.p}, {"u", r.u}, {"area", r.a}, {"k", r.k}, {"u_mean_field", ls.separation(r.p)},
                        {"area_mean_field", ls.contact_fraction(r.p)},
                        {"k_mean_field", effective_medium_conductance({ls.contact_fraction(r.p), ls.separation(r.p), rms})}});
    for (double L : st.drainage) {
      const SqueezeSetup setup{st.pressure, water_viscosity(20), L, st.film};
      const SqueezeHistory hm(mean_field, setup), hmap(on_map, setup);
      nlohmann::json row = {{"h0", h0},
                            {"drainage_length", L},
                            {"mean_field", summary(hm, st.patch_time)},
                            {"map", summary(hmap, st.patch_time)}};
      row["mean_field"]["u_equilibrium"] = ls.separation(st.pressure);
      row["mean_field"]["area_equilibrium"] = ls.contact_fraction(st.pressure);
      row["map"]["u_equilibrium"] = on_map.separation(st.pressure);
      row["map"]["area_equilibrium"] = on_map.contact(st.pressure);
      row["ladder"] = ladder;
      out.push_back(row);
    }
    std::fprintf(stderr, "  h0 %.3g mm done\n", 1e3 * h0);
  }
  return {{"rows", out}, {"young", st.young}, {"poisson", st.poisson}, {"pressure", st.pressure}, {"film", st.film},
          {"patch_time", st.patch_time}};
}

}  // namespace wr::bench
