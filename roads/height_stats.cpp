#include "roads/height_stats.hpp"

#include <cmath>

#include <array>
#include <vector>

#include "lib/core/parallel.hpp"

namespace wr {
namespace {

// Sums of f(row) over all rows, per fixed chunk, combined in order.
template <std::size_t K, class F>
std::array<double, K> row_sums(std::size_t rows, int threads, F&& f) {
  const std::size_t chunks = default_chunks(rows);
  std::vector<std::array<double, K>> part(chunks);
  parallel_chunks(rows, chunks, threads, [&](std::size_t c, std::size_t r0, std::size_t r1) {
    std::array<double, K> acc{};
    for (std::size_t r = r0; r < r1; ++r) f(r, acc);
    part[c] = acc;
  });
  std::array<double, K> total{};
  for (const auto& p : part)
    for (std::size_t k = 0; k < K; ++k) total[k] += p[k];
  return total;
}

}  // namespace

HeightStats height_stats(const HeightMap& m, int threads) {
  HeightStats s;
  const double n = static_cast<double>(m.h.size());
  const auto mean = row_sums<1>(m.ny, threads, [&](std::size_t iy, std::array<double, 1>& a) {
    double r = 0;
    for (std::size_t ix = 0; ix < m.nx; ++ix) r += m(ix, iy);
    a[0] += r;
  });
  s.mean = mean[0] / n;
  const auto mom = row_sums<4>(m.ny, threads, [&](std::size_t iy, std::array<double, 4>& a) {
    double ra = 0, r2 = 0, r3 = 0, r4 = 0;
    for (std::size_t ix = 0; ix < m.nx; ++ix) {
      const double d = m(ix, iy) - s.mean, d2 = d * d;
      ra += std::fabs(d);
      r2 += d2;
      r3 += d2 * d;
      r4 += d2 * d2;
    }
    a[0] += ra;
    a[1] += r2;
    a[2] += r3;
    a[3] += r4;
  });
  s.sq = std::sqrt(mom[1] / n);
  s.sa = mom[0] / n;
  if (s.sq > 0) {
    s.ssk = (mom[2] / n) / (s.sq * s.sq * s.sq);
    s.sku = (mom[3] / n) / (s.sq * s.sq * s.sq * s.sq);
  }
  return s;
}

double rms_slope_finite_difference(const HeightMap& m, int threads, SlopeStencil stencil) {
  const std::size_t nx = m.nx, ny = m.ny;
  // A difference at i spans [i - back, i + 1]: back 0 forward (over dx), back 1 central (over 2 dx).
  const std::size_t back = stencil == SlopeStencil::central ? 1 : 0;
  const double span = double(back + 1);
  const std::size_t ex = m.periodic ? nx : nx - 1 - back;  // x differences per row
  const std::size_t ey = m.periodic ? ny : ny - 1 - back;  // rows with a y difference
  // Neighbours with periodic wrap-around, by comparison rather than a modulo in the inner loop.
  const auto next = [](std::size_t i, std::size_t n) { return i + 1 == n ? 0 : i + 1; };
  const auto prev = [back](std::size_t i, std::size_t n) { return back == 0 ? i : (i == 0 ? n - 1 : i - 1); };
  const auto g = row_sums<2>(ny, threads, [&](std::size_t iy, std::array<double, 2>& a) {
    double gx = 0, gy = 0;
    for (std::size_t k = 0; k < ex; ++k) {
      const std::size_t ix = m.periodic ? k : k + back;  // the difference's centre
      const double d = (m(next(ix, nx), iy) - m(prev(ix, nx), iy)) / (span * m.dx);
      gx += d * d;
    }
    const bool has_y = m.periodic ? true : (iy >= back && iy + 1 < ny);
    if (!m.is_profile() && has_y) {
      const std::size_t jy = next(iy, ny), ky = prev(iy, ny);
      for (std::size_t ix = 0; ix < nx; ++ix) {
        const double d = (m(ix, jy) - m(ix, ky)) / (span * m.dy);
        gy += d * d;
      }
    }
    a[0] += gx;
    a[1] += gy;
  });
  const double mean_gx2 = g[0] / double(ex * ny);
  if (m.is_profile()) return std::sqrt(2.0 * mean_gx2);
  return std::sqrt(mean_gx2 + g[1] / double(ey * nx));
}

}  // namespace wr
