// Benchmarks of the thin-film flow on the map (bench/bench_flow.hpp).
#include "bench/bench_flow.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "bench/bench_common.hpp"
#include "lib/flow/contact_gap.hpp"
#include "lib/flow/effective_medium.hpp"
#include "lib/flow/thin_film_flow.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "roads/height_stats.hpp"
#include "roads/synthesize.hpp"

namespace wr::bench {
namespace {

// The rubber of the flow benches (a tread compound's rubbery plateau); results are reported
// against sigma*, which makes them independent of E and of the height scale.
const ElasticBody kRubber{10e6, 0.45};

// sigma* -> mean pressure (Pa) on `map`: sigma* E* rms slope (design.md, eq. 5.2).
double pressure_of(double sigma_star, double rms_slope) { return sigma_star * kRubber.e_star() * rms_slope; }

// One contact state: its area fraction, mean gap and the percolation of its free area.
struct ContactState {
  double sigma_star = 0, area = 0, mean_gap = 0, contact_s = 0;
  Percolation perc;
  HeightMap gap;
};

ContactState solve_at(SpectralNormalContact& solver, const HeightMap& map, double rms_slope, double sigma_star,
                      const SpectralOptions& opt) {
  ContactState s;
  s.sigma_star = sigma_star;
  const SpectralNormalResult r = solver.solve_load(pressure_of(sigma_star, rms_slope), opt);
  if (!r.converged) std::fprintf(stderr, "  warning: contact at sigma* %.4g not converged: %s\n", sigma_star, r.message.c_str());
  s.contact_s = r.wall_s;
  s.gap = contact_gap_map(map, solver.pressure(), solver.gap());
  s.area = contact_fraction(s.gap);
  double sum = 0;
  for (double g : s.gap.h) sum += g;
  s.mean_gap = sum / double(s.gap.size());
  s.perc = free_area_percolation(s.gap);
  return s;
}

nlohmann::json conductance_json(const FlowConductance& k) {
  return {{"kxx", k.kxx}, {"kyy", k.kyy}, {"kxy", k.kxy}, {"kyx", k.kyx}, {"wall_s", k.wall_s},
          {"iterations", k.iterations}, {"residual", k.residual}, {"solver", k.solver}};
}

// The area fractions bracketing the threshold in one direction: the largest area seen that still
// percolates and the smallest that does not (with their sigma*).
struct Bracket {
  double sigma_lo = 0, area_lo = 0, sigma_hi = 0, area_hi = 1;
  bool found_lo = false, found_hi = false;
};

Bracket bracket_of(const std::vector<ContactState>& seen, bool in_x) {
  Bracket b;
  for (const ContactState& s : seen) {
    const bool p = in_x ? s.perc.x : s.perc.y;
    if (p && (!b.found_lo || s.sigma_star > b.sigma_lo)) b = {s.sigma_star, s.area, b.sigma_hi, b.area_hi, true, b.found_hi};
    if (!p && (!b.found_hi || s.sigma_star < b.sigma_hi)) b = {b.sigma_lo, b.area_lo, s.sigma_star, s.area, b.found_lo, true};
  }
  return b;
}

// Bisection in log sigma* until the area bracket is narrower than `area_resolution`; every state
// solved is kept in `seen` (the other direction starts from them).
Bracket elastic_threshold(SpectralNormalContact& solver, const HeightMap& map, double rms_slope, const SpectralOptions& opt,
                          std::vector<ContactState>& seen, bool in_x, double area_resolution = 0.002) {
  Bracket b = bracket_of(seen, in_x);
  for (int guard = 0; !b.found_lo && guard < 8; ++guard) {
    seen.push_back(solve_at(solver, map, rms_slope, (b.found_hi ? b.sigma_hi : 0.05) / 2, opt));
    b = bracket_of(seen, in_x);
  }
  for (int guard = 0; !b.found_hi && guard < 8; ++guard) {
    seen.push_back(solve_at(solver, map, rms_slope, b.sigma_lo * 2, opt));
    b = bracket_of(seen, in_x);
  }
  for (int it = 0; b.found_lo && b.found_hi && b.area_hi - b.area_lo > area_resolution && it < 30; ++it) {
    seen.push_back(solve_at(solver, map, rms_slope, std::sqrt(b.sigma_lo * b.sigma_hi), opt));
    b = bracket_of(seen, in_x);
  }
  return b;
}

// The rigid flat: the k highest points in contact; bisection on k for the last percolating k.
std::pair<double, double> rigid_threshold(const HeightMap& map, bool in_x) {
  const std::size_t n = map.size();
  std::size_t lo = 1, hi = n - 1;  // lo percolates, hi does not (a single free point winds nowhere in general)
  auto perc = [&](std::size_t k) {
    const Percolation p = free_area_percolation(rigid_flat_gap(map, level_at_contact_fraction(map, double(k) / double(n))));
    return in_x ? p.x : p.y;
  };
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (perc(mid) ? lo : hi) = mid;
  }
  return {double(lo) / double(n), double(hi) / double(n)};
}

}  // namespace

HeightMap flow_surface(std::size_t n, double hurst, std::uint64_t seed, double q0_ratio, double cells_per_wavelength,
                       int threads) {
  SynthParams p;
  p.nx = p.ny = n;
  p.dx = 1e-2 / double(n);
  p.h0 = 1e-5;
  p.hurst = hurst;
  p.q0_ratio = q0_ratio;
  p.q1 = 2 * std::numbers::pi / (cells_per_wavelength * p.dx);
  p.seed = seed;
  p.threads = threads;
  return synthesize(p).map;
}

nlohmann::json flow_speed(const std::vector<std::size_t>& sizes, double sigma_star, std::uint64_t seed, int threads) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t n : sizes) {
    const HeightMap map = flow_surface(n, 0.8, seed, 4, 8, threads);
    const double slope = rms_slope_finite_difference(map, threads);
    SpectralNormalContact solver(map, kRubber, threads, FftPlanning::estimate);
    SpectralOptions opt;
    opt.tolerance = 1e-8;
    opt.threads = threads;
    const ContactState s = solve_at(solver, map, slope, sigma_star, opt);
    FlowOptions fo;
    fo.solver = FlowSolver::cholmod;
    const FlowConductance d = thin_film_conductance(s.gap, fo);
    fo.solver = FlowSolver::amg;
    const FlowConductance a = thin_film_conductance(s.gap, fo);
    const double scale = std::max(std::abs(d.kxx), std::abs(d.kyy));
    double diff = 0;
    for (auto [x, y] : {std::pair{a.kxx, d.kxx}, {a.kyy, d.kyy}, {a.kxy, d.kxy}}) diff = std::max(diff, std::abs(x - y) / scale);
    std::fprintf(stderr, "  %zu^2: contact %.2f s, cholmod %.2f s, amg %.2f s\n", n, s.contact_s, d.wall_s, a.wall_s);
    rows.push_back({{"n", n}, {"area_fraction", s.area}, {"mean_gap", s.mean_gap}, {"contact_s", s.contact_s},
                    {"unknowns", d.unknowns}, {"cholmod", conductance_json(d)}, {"amg", conductance_json(a)},
                    {"max_relative_difference", diff}});
  }
  return {{"sigma_star", sigma_star}, {"seed", seed}, {"hurst", 0.8}, {"rows", rows}};
}

nlohmann::json percolation_threshold(const PercolationSetup& st) {
  nlohmann::json maps = nlohmann::json::array();
  for (double hurst : st.hursts)
    for (std::size_t si = 0; si < st.seeds.size(); ++si) {
      const double t0 = now();
      const HeightMap map = flow_surface(st.n, hurst, st.seeds[si], st.q0_ratio, st.cells_per_wavelength, st.threads);
      const double slope = rms_slope_finite_difference(map, st.threads);
      SpectralNormalContact solver(map, kRubber, st.threads, FftPlanning::estimate);
      SpectralOptions opt;
      opt.tolerance = st.contact_tolerance;
      opt.threads = st.threads;
      std::vector<ContactState> seen;
      const Bracket ex = elastic_threshold(solver, map, slope, opt, seen, true);
      const Bracket ey = elastic_threshold(solver, map, slope, opt, seen, false);
      const auto rx = rigid_threshold(map, true), ry = rigid_threshold(map, false);
      nlohmann::json row = {{"seed", st.seeds[si]},
                            {"hurst", hurst},
                            {"rms_slope", slope},
                            {"elastic_x", {ex.area_lo, ex.area_hi}},
                            {"elastic_y", {ey.area_lo, ey.area_hi}},
                            {"sigma_star_x", {ex.sigma_lo, ex.sigma_hi}},
                            {"sigma_star_y", {ey.sigma_lo, ey.sigma_hi}},
                            {"rigid_x", {rx.first, rx.second}},
                            {"rigid_y", {ry.first, ry.second}},
                            {"contact_solves", seen.size()}};
      if (si == 0) {  // the conductance ladder of this H's first map
        // the mean-field rung beside it: Bruggeman's medium from A/A0, the mean gap and the map's rms
        double rms = 0;
        for (double h : map.h) rms += h * h;
        rms = std::sqrt(rms / static_cast<double>(map.size()));
        nlohmann::json ladder = nlohmann::json::array();
        for (double s : st.ladder) {
          const ContactState c = solve_at(solver, map, slope, s, opt);
          const FlowConductance k = thin_film_conductance(c.gap, {});
          ladder.push_back({{"sigma_star", s}, {"pressure", pressure_of(s, slope)}, {"area_fraction", c.area},
                            {"mean_gap", c.mean_gap}, {"kxx", k.kxx}, {"kyy", k.kyy}, {"kxy", k.kxy},
                            {"percolates_x", k.percolates_x}, {"percolates_y", k.percolates_y}, {"flow_s", k.wall_s},
                            {"k_effective_medium", effective_medium_conductance({c.area, c.mean_gap, rms})}});
        }
        row["ladder"] = ladder;
      }
      row["wall_s"] = now() - t0;
      std::fprintf(stderr, "  H %.1f seed %llu: elastic x %.3f y %.3f, rigid x %.3f y %.3f (%zu contact solves, %.1f s)\n",
                   hurst, static_cast<unsigned long long>(st.seeds[si]), 0.5 * (ex.area_lo + ex.area_hi),
                   0.5 * (ey.area_lo + ey.area_hi), 0.5 * (rx.first + rx.second), 0.5 * (ry.first + ry.second),
                   seen.size(), now() - t0);
      maps.push_back(row);
    }
  return {{"n", st.n}, {"q0_ratio", st.q0_ratio}, {"cells_per_wavelength", st.cells_per_wavelength},
          {"contact_tolerance", st.contact_tolerance}, {"e", kRubber.young}, {"nu", kRubber.poisson}, {"maps", maps}};
}

}  // namespace wr::bench
