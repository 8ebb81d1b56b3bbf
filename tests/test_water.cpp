// Water: exact answers on hand-made surfaces and properties on random self-affine surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "lib/core/errors.hpp"
#include "roads/synthesize.hpp"
#include "water/depression_hierarchy.hpp"
#include "water/drained_limit.hpp"
#include "water/fill_spill_merge.hpp"
#include "water/rain_fill.hpp"

namespace wr {
namespace {

HeightMap make_map(std::size_t nx, std::size_t ny, const std::function<double(long, long)>& f) {
  HeightMap m(nx, ny, 1e-4, 1e-4);
  m.periodic = true;
  for (std::size_t iy = 0; iy < ny; ++iy)
    for (std::size_t ix = 0; ix < nx; ++ix) m(ix, iy) = f(long(ix), long(iy));
  return m;
}

// Brute-force stored volume of a lake at level z over the given cells (m x cells).
double volume_below(const HeightMap& m, const std::vector<std::size_t>& cells, double z) {
  double v = 0;
  for (std::size_t c : cells) v += std::max(0.0, z - m.h[c]);
  return v;
}

// Level z with volume_below(z) = v, by bisection (independent of the library's inversion).
double level_for(const HeightMap& m, const std::vector<std::size_t>& cells, double v) {
  double lo = -10, hi = 10;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (volume_below(m, cells, mid) < v ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// A paraboloid bowl of radius 6 cells, depth 1 (units), in a flat plateau at height 1; the
// distance to the centre is periodic, so a bowl at the corner crosses both seams.
HeightMap one_bowl(long cx = 10, long cy = 10) {
  return make_map(20, 20, [=](long x, long y) {
    const long dx = std::min(std::labs(x - cx), 20 - std::labs(x - cx));
    const long dy = std::min(std::labs(y - cy), 20 - std::labs(y - cy));
    return std::min(1.0, double(dx * dx + dy * dy) / 36.0);
  });
}

TEST(WaterExact, OneBowlHoldsAllTheRainAtAFlatLevel) {
  const HeightMap m = one_bowl();
  const DepressionHierarchy dh(m, 4, Boundary::torus);
  std::vector<std::size_t> bowl;
  for (std::size_t c = 0; c < m.h.size(); ++c)
    if (m.h[c] < 1) bowl.push_back(c);
  const double capacity = volume_below(m, bowl, 1.0);
  for (double d : {0.001, 0.01, 0.05}) {
    const double v = d * m.h.size();  // all rain runs into the bowl
    ASSERT_LT(v, capacity);
    const WaterState w = fill_spill_merge(dh, d, WaterMode::drained);
    const double z = level_for(m, bowl, v);
    for (std::size_t c = 0; c < m.h.size(); ++c) EXPECT_NEAR(w.level[c], std::max(m.h[c], z), 1e-9) << c;
    EXPECT_NEAR(w.stored_volume * m.h.size(), v, 1e-9);
    EXPECT_NEAR(w.drained_volume, 0.0, 1e-15);
    EXPECT_EQ(w.lakes, 1u);
  }
  // More rain than the bowl holds: full to the plateau, the rest drains (the plateau wraps).
  const WaterState w = fill_spill_merge(dh, 1.0, WaterMode::drained);
  for (std::size_t c : bowl) EXPECT_NEAR(w.level[c], 1.0, 1e-12);
  EXPECT_NEAR(w.drained_volume * m.h.size(), m.h.size() * 1.0 - capacity, 1e-9);
}

TEST(WaterExact, FlatBottomedPoolAndStagnantFlooding) {
  // 8x8 pool with a flat bottom at 0 in a plateau at 1: coverage jumps to 64/400 with any rain.
  const HeightMap m = make_map(20, 20, [](long x, long y) { return (x >= 6 && x < 14 && y >= 6 && y < 14) ? 0.0 : 1.0; });
  const DepressionHierarchy dh(m, 4, Boundary::torus);
  WaterState w = fill_spill_merge(dh, 1e-6, WaterMode::drained);
  EXPECT_NEAR(w.coverage, 64.0 / 400, 1e-15);
  w = fill_spill_merge(dh, 0.1, WaterMode::drained);
  EXPECT_NEAR(w.level[10 * 20 + 10], 0.1 * 400 / 64, 1e-12);
  // Stagnant beyond the brim: V(z) = 64 z + 336 (z - 1) for z >= 1.
  w = fill_spill_merge(dh, 0.5, WaterMode::stagnant);
  const double z = (0.5 * 400 + 336) / 400;
  for (std::size_t c = 0; c < m.h.size(); ++c) EXPECT_NEAR(w.level[c], z, 1e-12);
  EXPECT_NEAR(w.coverage, 1.0, 0);
  EXPECT_NEAR(w.stored_volume, 0.5, 1e-13);
}

TEST(WaterExact, TwoBowlsFillLowerFirstThenSpillAndMerge) {
  // Pool A (floor 0) and pool B (floor 0.2), 5x5 cells each, joined by a one-cell channel at
  // 0.5; plateau at 1. Expected levels follow from the rain each pool collects (from the
  // routing rule, read off the hierarchy) and the flat floors.
  const HeightMap m = make_map(24, 12, [](long x, long y) {
    if (y >= 3 && y < 8 && x >= 3 && x < 8) return 0.0;    // A
    if (y >= 3 && y < 8 && x >= 9 && x < 14) return 0.2;   // B
    if (y == 5 && x == 8) return 0.5;                      // saddle
    return 1.0;
  });
  const DepressionHierarchy dh(m, 4, Boundary::torus);
  const std::size_t ia = 5 * 24 + 5, ib = 5 * 24 + 11, saddle = 5 * 24 + 8;
  const int leaf_a = dh.owner(ia), leaf_b = dh.owner(ib);
  ASSERT_NE(leaf_a, leaf_b);
  double rain_a = 0, rain_b = 0;  // cells whose rain reaches each pool (routing rule)
  for (std::uint32_t c = 0; c < dh.cells(); ++c) {
    rain_a += dh.rain_node(c) == leaf_a;
    rain_b += dh.rain_node(c) == leaf_b;
  }
  ASSERT_EQ(rain_a + rain_b, double(dh.cells()));
  EXPECT_EQ(dh.rain_node(saddle), leaf_a);  // the saddle drains to the steeper side, A
  // Small rain: each pool holds its own catchment's water.
  double d = 0.02;
  WaterState w = fill_spill_merge(dh, d, WaterMode::drained);
  EXPECT_NEAR(w.level[ia], rain_a * d / 25, 1e-12);
  EXPECT_NEAR(w.level[ib], 0.2 + rain_b * d / 25, 1e-12);
  EXPECT_EQ(w.lakes, 2u);
  // More rain: the pool whose catchment fills it first (to the saddle at 0.5) overflows into
  // the other one, which is not full yet.
  const double cap_a = 25 * 0.5, cap_b = 25 * 0.3;
  const bool b_first = cap_b / rain_b < cap_a / rain_a;
  d = 1.1 * (b_first ? cap_b / rain_b : cap_a / rain_a);
  ASSERT_LT(d * dh.cells(), cap_a + cap_b);
  w = fill_spill_merge(dh, d, WaterMode::drained);
  if (b_first) {
    EXPECT_NEAR(w.level[ib], 0.5, 1e-12);
    EXPECT_NEAR(w.level[ia], (d * dh.cells() - cap_b) / 25, 1e-12);
  } else {
    EXPECT_NEAR(w.level[ia], 0.5, 1e-12);
    EXPECT_NEAR(w.level[ib], 0.2 + (d * dh.cells() - cap_a) / 25, 1e-12);
  }
  EXPECT_DOUBLE_EQ(w.level[saddle], 0.5);  // at the saddle: not above it, so dry
  // Both full: one lake over A, B and the saddle, rising above 0.5 (below the plateau).
  d = (12.5 + 7.5 + 10) / double(dh.cells());
  w = fill_spill_merge(dh, d, WaterMode::drained);
  const double z = 0.5 + (d * dh.cells() - 12.5 - 7.5) / 51.0;
  EXPECT_NEAR(w.level[ia], z, 1e-12);
  EXPECT_NEAR(w.level[ib], z, 1e-12);
  EXPECT_NEAR(w.level[saddle], z, 1e-12);
  EXPECT_EQ(w.lakes, 1u);
}

TEST(WaterExact, CraterOnAHillFillsToItsRim) {
  // A cone hill with a crater; the crater's limit level is the lowest point of its rim.
  const HeightMap m = make_map(32, 32, [](long x, long y) {
    const double r = std::hypot(double(x - 16), double(y - 16));
    double h = std::max(0.0, 10.0 - r);            // cone
    if (r < 3.5) h = 6.5 + 0.3 * r + 0.01 * x;     // crater floor rising to a tilted rim
    return h;
  });
  const BigVector lim = drained_limit_levels(m, 4, Boundary::torus);
  // Independent minimax: relax level = max(h, min over 4-neighbours' levels) from the flat
  // ground around the hill (height 0, which wraps around the torus: the way out).
  std::vector<double> ref(m.h.size(), 1e9);
  for (std::size_t c = 0; c < m.h.size(); ++c)
    if (m.h[c] == 0.0) ref[c] = 0.0;
  for (bool changed = true; changed;) {
    changed = false;
    for (long y = 0; y < 32; ++y)
      for (long x = 0; x < 32; ++x) {
        const std::size_t c = std::size_t(y * 32 + x);
        double lo = 1e9;
        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
          lo = std::min(lo, ref[std::size_t(((y + dy + 32) % 32) * 32 + (x + dx + 32) % 32)]);
        const double v = std::max(m.h[c], lo);
        if (v < ref[c]) {
          ref[c] = v;
          changed = true;
        }
      }
  }
  for (std::size_t c = 0; c < m.h.size(); ++c) EXPECT_DOUBLE_EQ(lim[c], ref[c]) << c;
  EXPECT_GT(lim[16 * 32 + 16], m(16, 16));              // the crater holds water
  EXPECT_NEAR(lim[16 * 32 + 16], lim[16 * 32 + 17], 0);  // flat
  EXPECT_DOUBLE_EQ(lim[2 * 32 + 2], m(2, 2));           // the slopes stay dry
  // Fill-spill-merge with plenty of rain reaches the same limit.
  const DepressionHierarchy dh(m, 4, Boundary::torus);
  const WaterState w = fill_spill_merge(dh, 100.0, WaterMode::drained);
  for (std::size_t c = 0; c < m.h.size(); ++c) EXPECT_NEAR(w.level[c], lim[c], 1e-9);
}

TEST(WaterExact, PoolAcrossTheSeamAndCornerEqualsTheCentredPool) {
  const HeightMap centred = one_bowl(10, 10), corner = one_bowl(0, 0);
  const DepressionHierarchy a(centred, 4, Boundary::torus), b(corner, 4, Boundary::torus);
  const WaterState wa = fill_spill_merge(a, 0.03, WaterMode::drained);
  const WaterState wb = fill_spill_merge(b, 0.03, WaterMode::drained);
  for (long y = 0; y < 20; ++y)
    for (long x = 0; x < 20; ++x) EXPECT_NEAR(wa.level[y * 20 + x], wb.level[((y + 10) % 20) * 20 + (x + 10) % 20], 1e-12);
  EXPECT_EQ(wb.lakes, 1u);  // one lake, though it touches all four edges
}

TEST(WaterExact, LongDiagonalTrenchBreaksTheThreeByThreeTiling) {
  // A trench 1.5 tiles long running at slope 1/4: it does not reach its own image, so on the
  // torus it fills to the plateau, but its copy in the 3x3 tiling reaches the border.
  const long N = 64;
  const HeightMap m = make_map(N, N, [&](long x, long y) {
    for (long t = 0; t < 96; ++t)  // a 4-connected staircase: a step up after every 4 cells
      if ((t % N) == x && ((t / 4) % N == y || ((t + 1) / 4) % N == y)) return 0.0;
    return 1.0;
  });
  FillRequest req;
  req.limit = true;
  const FillResult torus = fill_water(m, req);
  req.tiling = Tiling::three_by_three;
  const FillResult tiled = fill_water(m, req);
  ASSERT_TRUE(tiled.tiling_differing_cells.has_value());
  EXPECT_GT(*tiled.tiling_differing_cells, 0u);
  EXPECT_FALSE(tiled.warnings.empty());
  EXPECT_GT(torus.water.coverage, tiled.water.coverage);
  // A short trench (shorter than the tile): both methods agree.
  const HeightMap s = make_map(N, N, [&](long x, long y) { return (y == 20 && x >= 10 && x < 30) ? 0.0 : 1.0; });
  req.tiling = Tiling::three_by_three;
  const FillResult ok = fill_water(s, req);
  EXPECT_EQ(*ok.tiling_differing_cells, 0u);
}

TEST(WaterExact, CorrugationHasNoPools) {
  const HeightMap m = make_map(32, 16, [](long x, long) { return std::sin(2 * M_PI * double(x) / 32.0); });
  const DepressionHierarchy dh(m, 4, Boundary::torus);
  EXPECT_EQ(fill_spill_merge(dh, 0.01, WaterMode::drained).coverage, 0.0);
  const BigVector lim = drained_limit_levels(m, 8, Boundary::torus);
  for (std::size_t c = 0; c < m.h.size(); ++c) EXPECT_EQ(lim[c], m.h[c]);
}

// ---- properties on random self-affine surfaces ----

HeightMap random_surface(std::uint64_t seed, std::size_t n = 64) {
  SynthParams p;
  p.nx = p.ny = n;
  p.dx = 1e-4;
  p.h0 = 3e-4;
  p.seed = seed;
  return synthesize(p).map;
}

HeightMap shifted(const HeightMap& m, long sx, long sy) {
  HeightMap s = m;
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix) s((ix + sx) % m.nx, (iy + sy) % m.ny) = m(ix, iy);
  return s;
}

class WaterProperties : public ::testing::TestWithParam<int> {};

TEST_P(WaterProperties, CyclicShiftAndTransposeEquivariance) {
  const int conn = GetParam();
  const HeightMap m = random_surface(21);
  const HeightMap s = shifted(m, 17, 40);
  HeightMap t = m;  // transpose: changes every index, hence the processing order
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix) t(iy, ix) = m(ix, iy);
  const DepressionHierarchy dm(m, conn, Boundary::torus), ds(s, conn, Boundary::torus), dt(t, conn, Boundary::torus);
  for (WaterMode mode : {WaterMode::drained, WaterMode::stagnant})
    for (double d : {2e-6, 2e-5, 1e-4}) {
      const WaterState a = fill_spill_merge(dm, d, mode), b = fill_spill_merge(ds, d, mode),
                       c = fill_spill_merge(dt, d, mode);
      for (std::size_t iy = 0; iy < m.ny; ++iy)
        for (std::size_t ix = 0; ix < m.nx; ++ix) {
          const double la = a.level[iy * m.nx + ix];
          EXPECT_NEAR(la, b.level[((iy + 40) % m.ny) * m.nx + (ix + 17) % m.nx], 1e-15);
          EXPECT_NEAR(la, c.level[ix * m.nx + iy], 1e-15);
        }
    }
  const BigVector la = drained_limit_levels(m, conn, Boundary::torus), lb = drained_limit_levels(s, conn, Boundary::torus);
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix)
      EXPECT_EQ(la[iy * m.nx + ix], lb[((iy + 40) % m.ny) * m.nx + (ix + 17) % m.nx]);
}

TEST_P(WaterProperties, MonotoneConservativeAndBoundedByTheLimit) {
  const int conn = GetParam();
  for (std::uint64_t seed : {3u, 4u, 5u}) {
    const HeightMap m = random_surface(seed);
    const DepressionHierarchy dh(m, conn, Boundary::torus);
    const BigVector lim = drained_limit_levels(m, conn, Boundary::torus);
    double last_cov = 0;
    for (double d : {0.0, 1e-7, 1e-6, 5e-6, 1e-5, 3e-5, 1e-4, 3e-4, 1e-3}) {
      const WaterState w = fill_spill_merge(dh, d, WaterMode::drained);
      EXPECT_GE(w.coverage, last_cov) << "seed " << seed << " d " << d;
      last_cov = w.coverage;
      EXPECT_NEAR(w.stored_volume + w.drained_volume, d, 1e-12 * (1 + d));
      for (std::size_t c = 0; c < m.h.size(); ++c) {
        EXPECT_GE(w.level[c], m.h[c]);
        EXPECT_LE(w.level[c], lim[c] + 1e-15);
      }
      const WaterState st = fill_spill_merge(dh, d, WaterMode::stagnant);
      EXPECT_NEAR(st.stored_volume, d, 1e-12 * d + 1e-300);
      EXPECT_EQ(st.drained_volume, 0.0);
    }
    // Large rain drains to exactly the spill-level limit.
    const WaterState big = fill_spill_merge(dh, 1.0, WaterMode::drained);
    for (std::size_t c = 0; c < m.h.size(); ++c) EXPECT_NEAR(big.level[c], lim[c], 1e-15);
  }
}

INSTANTIATE_TEST_SUITE_P(Connectivity, WaterProperties, ::testing::Values(4, 8));

TEST(WaterRequests, BadInputsAreRefused) {
  const HeightMap m = random_surface(9, 32);
  FillRequest r;
  r.rain = -1;
  EXPECT_THROW(fill_water(m, r), InputError);
  r.rain = NAN;
  EXPECT_THROW(fill_water(m, r), InputError);
  r.rain.reset();
  r.coverage = 0.99;  // beyond the drained limit
  EXPECT_THROW(fill_water(m, r), InputError);
  r.mode = WaterMode::stagnant;
  const FillResult st = fill_water(m, r);
  EXPECT_NEAR(st.water.coverage, 0.99, 1.0 / 1024 + 1e-12);
  HeightMap holes = m;
  holes.h[5] = NAN;
  r.mode = WaterMode::drained;
  r.coverage = 0.2;
  EXPECT_THROW(fill_water(holes, r), InputError);
}

TEST(WaterRequests, CoverageTargetInsideAJumpIsReported) {
  // A flat-bottomed pool covers 64/400 = 16% with the first drop: 10% lies inside the jump.
  const HeightMap m = make_map(20, 20, [](long x, long y) { return (x >= 6 && x < 14 && y >= 6 && y < 14) ? 0.0 : 1.0; });
  FillRequest r;
  r.coverage = 0.10;
  const FillResult f = fill_water(m, r);
  EXPECT_TRUE(f.target_in_jump);
  EXPECT_DOUBLE_EQ(f.jump_low, 0.0);
  EXPECT_DOUBLE_EQ(f.jump_high, 0.16);
  EXPECT_FALSE(f.warnings.empty());
}

TEST(WaterRequests, CoverageTargetIsMetWithinOneCell) {
  const HeightMap m = random_surface(11, 64);
  FillRequest r;
  r.coverage = 0.25;
  const FillResult f = fill_water(m, r);
  EXPECT_NEAR(f.water.coverage, 0.25, 1.0 / 4096 + 1e-12);
  EXPECT_GT(f.water.rain_depth, 0);
}

}  // namespace
}  // namespace wr
