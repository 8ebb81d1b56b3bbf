#include "water/rain_fill.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "lib/core/errors.hpp"
#include "water/drained_limit.hpp"

namespace wr {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string pct(double f) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f%%", 100 * f);
  return b;
}

std::vector<double> ground_of(const HeightMap& m) { return {m.h.begin(), m.h.end()}; }

WaterState state_from_levels(const HeightMap& m, BigVector level, double rain, int connectivity) {
  WaterState w;
  w.level = std::move(level);
  w.rain_depth = rain;
  w.drained_volume = NAN;  // a level field alone says nothing about what drained
  summarize_water(GridTopology(m.nx, m.ny, m.dx, m.dy, connectivity, Boundary::torus), ground_of(m), w);
  return w;
}

// Rain depth for a target coverage: bisection on d (coverage is monotone in d).
void bisect_coverage(const DepressionHierarchy& dh, const HeightMap& m, const FillRequest& req, FillResult& out) {
  const double C = *req.coverage;
  const double tol = req.coverage_tolerance > 0 ? req.coverage_tolerance : 1.0 / double(m.h.size());
  double hmin = m.h[0], hmax = m.h[0];
  for (double v : m.h) {
    hmin = std::min(hmin, v);
    hmax = std::max(hmax, v);
  }
  double lo = 0, hi = 1.01 * (hmax - hmin) + 1e-12;  // hi floods every cell in stagnant mode
  WaterState w_hi = fill_spill_merge(dh, hi, req.mode);
  if (w_hi.coverage + tol < C) {
    throw InputError("--coverage", "a coverage of " + pct(C) + " cannot be reached in " +
                                       (req.mode == WaterMode::drained ? "drained" : "stagnant") +
                                       " mode: the most it holds is " + pct(w_hi.coverage) +
                                       (req.mode == WaterMode::drained ? " (the drained limit); use --stagnant for more" : ""));
  }
  WaterState w_lo = fill_spill_merge(dh, lo, req.mode);
  if (std::abs(w_lo.coverage - C) <= tol) {
    out.water = std::move(w_lo);
    return;
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15 * (1 + hi); ++it) {
    const double mid = 0.5 * (lo + hi);
    WaterState w = fill_spill_merge(dh, mid, req.mode);
    if (std::abs(w.coverage - C) <= tol) {
      out.water = std::move(w);
      return;
    }
    if (w.coverage < C) {
      lo = mid;
      w_lo = std::move(w);
    } else {
      hi = mid;
      w_hi = std::move(w);
    }
  }
  // The bracket shrank to nothing without reaching the target: coverage jumps there.
  out.target_in_jump = true;
  out.jump_low = w_lo.coverage;
  out.jump_high = w_hi.coverage;
  const bool take_high = std::abs(w_hi.coverage - C) <= std::abs(w_lo.coverage - C);
  out.water = take_high ? std::move(w_hi) : std::move(w_lo);
  out.warnings.push_back("coverage " + pct(C) + " lies inside a jump of coverage(rain) from " + pct(out.jump_low) +
                         " to " + pct(out.jump_high) + " at rain " + std::to_string(out.water.rain_depth) +
                         " m (a lake spreads over a flat or percolates); the nearer side is returned");
}

WaterState run_request(const DepressionHierarchy& dh, const HeightMap& m, const FillRequest& req, FillResult& out) {
  if (req.coverage) {
    bisect_coverage(dh, m, req, out);
    return std::move(out.water);
  }
  return fill_spill_merge(dh, *req.rain, req.mode);
}

void validate(const HeightMap& map, const FillRequest& req) {
  const int requests = int(req.rain.has_value()) + int(req.coverage.has_value()) + int(req.limit);
  if (requests != 1) throw InputError("", "give exactly one of --rain, --coverage, --limit");
  if (req.rain && !(std::isfinite(*req.rain) && *req.rain >= 0))
    throw InputError("--rain", "must be a finite depth >= 0 m");
  if (req.coverage && !(*req.coverage > 0 && *req.coverage <= 1))
    throw InputError("--coverage", "must be a fraction in (0, 1]");
  if (req.limit && req.mode == WaterMode::stagnant)
    throw InputError("--limit", "the drained limit has no stagnant counterpart (a closed surface floods)");
  if (req.rule == FillRule::cap && !(std::isfinite(req.dmax) && req.dmax >= 0))
    throw InputError("--dmax", "must be a finite depth >= 0 m");
  if (req.connectivity != 4 && req.connectivity != 8) throw InputError("--connectivity", "must be 4 or 8");
  if (!map.periodic) throw InputError("", "the water module needs a periodic surface (this map is not marked periodic)");
  for (double v : map.h)
    if (!std::isfinite(v)) throw InputError("", "the surface has NaN/Inf heights; fill them first");
}

}  // namespace

HeightMap tile_3x3(const HeightMap& m) {
  HeightMap t(3 * m.nx, 3 * m.ny, m.dx, m.dy);
  t.periodic = false;
  for (std::size_t iy = 0; iy < t.ny; ++iy)
    for (std::size_t ix = 0; ix < t.nx; ++ix) t(ix, iy) = m(ix % m.nx, iy % m.ny);
  return t;
}

BigVector central_tile(const BigVector& f, std::size_t nx, std::size_t ny) {
  BigVector out(nx * ny);
  for (std::size_t iy = 0; iy < ny; ++iy)
    for (std::size_t ix = 0; ix < nx; ++ix) out[iy * nx + ix] = f[(iy + ny) * 3 * nx + ix + nx];
  return out;
}

FillResult fill_water(const HeightMap& map, const FillRequest& req) {
  validate(map, req);
  FillResult out;
  if (req.rule == FillRule::cap) {
    // Thesis's literal rule on top of the exact drained limit.
    const auto t0 = std::chrono::steady_clock::now();
    BigVector lim = drained_limit_levels(map, req.connectivity, Boundary::torus);
    for (std::size_t c = 0; c < lim.size(); ++c) lim[c] = std::min(lim[c], map.h[c] + req.dmax);
    out.water = state_from_levels(map, std::move(lim), NAN, req.connectivity);
    out.fill_s = seconds_since(t0);
    out.method = "cap rule (thesis, non-physical): level = min(spill level, h + dmax)";
    out.warnings.push_back("--rule cap is non-physical: its water is not flat and its coverage is the drained limit for any dmax > 0");
    return out;
  }
  auto t0 = std::chrono::steady_clock::now();
  WaterState exact;
  if (req.limit) {  // direct minimax: no hierarchy needed
    exact = state_from_levels(map, drained_limit_levels(map, req.connectivity, Boundary::torus), NAN, req.connectivity);
  } else {
    const DepressionHierarchy torus(map, req.connectivity, Boundary::torus);
    out.hierarchy_s = seconds_since(t0);
    out.hierarchy_nodes = torus.nodes().size();
    t0 = std::chrono::steady_clock::now();
    exact = run_request(torus, map, req, out);
  }
  out.fill_s = seconds_since(t0);
  out.method = req.limit ? "drained limit, exact periodic (minimax spill levels on the torus)"
                         : (req.mode == WaterMode::drained ? "fill-spill-merge, drained, exact periodic (torus)"
                                                           : "fill-spill-merge, stagnant, periodic and closed");
  if (req.tiling == Tiling::torus) {
    out.water = std::move(exact);
    return out;
  }
  // The thesis's 3x3 tiling: same request on the tiled, bounded map; keep the central tile.
  if (req.mode == WaterMode::stagnant)
    throw InputError("--tiling", "3x3 tiling drains through its border; it has no stagnant mode");
  const HeightMap big = tile_3x3(map);
  t0 = std::chrono::steady_clock::now();
  BigVector big_level;
  if (req.limit) {
    big_level = drained_limit_levels(big, req.connectivity, Boundary::outlet);
  } else {
    const DepressionHierarchy dh(big, req.connectivity, Boundary::outlet);
    FillRequest r = req;
    if (req.coverage) {  // the rain depth found on the torus, for a like-for-like comparison
      r.coverage.reset();
      r.rain = exact.rain_depth;
    }
    big_level = fill_spill_merge(dh, *r.rain, req.mode).level;
  }
  WaterState tiled = state_from_levels(map, central_tile(big_level, map.nx, map.ny), exact.rain_depth, req.connectivity);
  out.fill_s += seconds_since(t0);
  std::size_t differ = 0;
  double worst = 0;
  double scale = 0;
  for (double v : map.h) scale = std::max(scale, std::abs(v));
  for (std::size_t c = 0; c < map.h.size(); ++c) {
    const double d = std::abs(tiled.level[c] - exact.level[c]);
    if (d > 1e-12 * (1 + scale)) ++differ;
    worst = std::max(worst, d);
  }
  out.tiling_differing_cells = differ;
  out.tiling_max_difference = worst;
  out.method = "3x3 tiling (thesis): border as outlet, central tile kept";
  if (differ > 0)
    out.warnings.push_back("3x3 tiling FAILS here: " + std::to_string(differ) +
                           " cells differ from the exact periodic answer (by up to " + std::to_string(worst) +
                           " m): a lake is longer than the tile, so the central tile under-fills and its edges do not match");
  out.water = std::move(tiled);
  return out;
}

}  // namespace wr
