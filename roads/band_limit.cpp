#include "roads/band_limit.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "lib/core/fft.hpp"

namespace wr {

HeightMap band_limited(const HeightMap& map, double q_max, std::size_t refine, int threads) {
  if (!map.periodic) throw std::invalid_argument("band_limited: the map must be periodic");
  if (refine < 1 || refine > 64) throw std::invalid_argument("band_limited: refine must lie in 1 ... 64");
  if (!(q_max > 0)) throw std::invalid_argument("band_limited: q_max must be > 0");
  RealFft2d coarse(map.nx, map.ny, threads);
  std::copy(map.h.begin(), map.h.end(), coarse.real());
  coarse.forward();
  const std::size_t nx = map.nx * refine, ny = map.ny * refine;
  RealFft2d fine(nx, ny, threads);
  std::complex<double>* fs = fine.spectrum();
  std::fill(fs, fs + ny * fine.nxh(), std::complex<double>(0));
  const double scale = 1.0 / double(map.nx * map.ny);
  const double qx0 = 2 * std::numbers::pi / map.lx(), qy0 = 2 * std::numbers::pi / map.ly();
  for (std::size_t j = 0; j < map.ny; ++j) {
    const long jj = j <= map.ny / 2 ? long(j) : long(j) - long(map.ny);
    if (map.ny > 1 && 2 * std::size_t(std::labs(jj)) == map.ny) continue;  // Nyquist row
    const std::size_t row = std::size_t((jj + long(ny)) % long(ny));
    for (std::size_t i = 0; i < coarse.nxh(); ++i) {
      if (map.nx % 2 == 0 && i == map.nx / 2) continue;  // Nyquist column
      if (std::hypot(qx0 * double(i), qy0 * double(jj)) > q_max * (1 + 1e-12)) continue;
      fs[row * fine.nxh() + i] = coarse.spectrum()[j * coarse.nxh() + i] * scale;
    }
  }
  fine.backward();
  HeightMap out(nx, ny, map.dx / double(refine), map.dy / double(refine), map.kind);
  out.periodic = true;
  std::copy(fine.real(), fine.real() + nx * ny, out.h.begin());
  return out;
}

}  // namespace wr
