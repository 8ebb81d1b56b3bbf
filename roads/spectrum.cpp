#include "roads/spectrum.hpp"

#include <cmath>
#include <numbers>

#include "lib/core/fft.hpp"
#include "lib/core/parallel.hpp"

namespace wr {
namespace {

long signed_index(std::size_t i, std::size_t n) {
  return i <= n / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(n);
}

}  // namespace

SpectrumResult analyze_spectrum(const HeightMap& map, int threads) {
  const std::size_t nx = map.nx, ny = map.ny;
  // Out-of-place r2c preserves its input, so the map itself serves as the real array.
  RealFft2d fft(nx, ny, threads, const_cast<double*>(map.h.data()));
  fft.forward();
  const std::complex<double>* X = fft.spectrum();
  const std::size_t nxh = fft.nxh();
  const double norm = 1.0 / (static_cast<double>(nx) * static_cast<double>(ny));
  const double qLx = 2 * std::numbers::pi / map.lx();
  const double qLy = map.is_profile() ? qLx : 2 * std::numbers::pi / map.ly();
  const double dq = std::min(qLx, qLy);
  const double cell = map.is_profile() ? qLx : qLx * qLy;

  SpectrumResult r;
  r.nyquist = std::numbers::pi / std::max(map.dx, map.is_profile() ? map.dx : map.dy);
  const double qmax = std::hypot(qLx * (nx / 2), map.is_profile() ? 0.0 : qLy * (ny / 2));
  const std::size_t nbins = static_cast<std::size_t>(std::lround(qmax / dq)) + 2;
  // Partial sums per fixed chunk of rows, combined in chunk order (deterministic).
  struct Partial {
    double m0 = 0, m2 = 0, m4 = 0;
    std::vector<double> sum, cnt;
  };
  const std::size_t chunks = default_chunks(ny);
  std::vector<Partial> part(chunks);
  const bool profile = map.is_profile();
  parallel_chunks(ny, chunks, threads, [&](std::size_t c, std::size_t y0, std::size_t y1) {
    Partial& P = part[c];
    P.sum.assign(nbins, 0.0);
    P.cnt.assign(nbins, 0.0);
    for (std::size_t iy = y0; iy < y1; ++iy) {
      const double qy = signed_index(iy, ny) * qLy;
      for (std::size_t ix = 0; ix < nxh; ++ix) {
        if (ix == 0 && iy == 0) continue;
        const double qx = signed_index(ix, nx) * qLx;
        // Interior columns of the half spectrum stand for q and -q.
        const double w = (ix == 0 || (nx % 2 == 0 && ix == nx / 2)) ? 1.0 : 2.0;
        const double p = std::norm(X[iy * nxh + ix] * norm);  // |B_q|^2
        const double q2 = qx * qx + qy * qy;
        P.m0 += w * p;
        if (profile) {
          P.m2 += w * p * q2;
          P.m4 += w * p * q2 * q2;
        } else {
          P.m2 += w * p * q2 * 0.5;
          P.m4 += w * p * q2 * q2 * 0.375;
        }
        const std::size_t bin = static_cast<std::size_t>(std::sqrt(q2) / dq + 0.5);
        P.sum[bin] += w * p / cell;
        P.cnt[bin] += w;
      }
    }
  });
  std::vector<double> sum(nbins, 0.0), cnt(nbins, 0.0);
  double m0 = 0, m2 = 0, m4 = 0;
  for (const Partial& P : part) {
    m0 += P.m0;
    m2 += P.m2;
    m4 += P.m4;
    for (std::size_t b = 0; b < nbins; ++b) {
      sum[b] += P.sum[b];
      cnt[b] += P.cnt[b];
    }
  }
  r.moments = {m0, m2, m4};
  for (std::size_t b = 1; b < nbins; ++b) {
    if (cnt[b] == 0) continue;
    r.psd.q.push_back(b * dq);
    r.psd.C.push_back(sum[b] / cnt[b]);
    r.psd.count.push_back(cnt[b]);
  }
  return r;
}

}  // namespace wr
