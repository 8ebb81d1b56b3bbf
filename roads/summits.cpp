#include "roads/summits.hpp"

#include "lib/core/parallel.hpp"

namespace wr {

SummitStats find_summits(const HeightMap& m, double h0, int threads) {
  SummitStats s;
  const long nx = static_cast<long>(m.nx), ny = static_cast<long>(m.ny);
  const long lo = m.periodic ? 0 : 1;
  auto wrap = [](long i, long n) { return i < 0 ? i + n : (i >= n ? i - n : i); };
  const std::size_t rows = static_cast<std::size_t>(ny - 2 * lo);
  const std::size_t chunks = default_chunks(rows);
  std::vector<std::vector<double>> part(chunks);
  parallel_chunks(rows, chunks, threads, [&](std::size_t c, std::size_t r0, std::size_t r1) {
    for (long iy = lo + long(r0); iy < lo + long(r1); ++iy) {
      const long ym = wrap(iy - 1, ny), yp = wrap(iy + 1, ny);
      for (long ix = lo; ix < nx - lo; ++ix) {
        const long xm = wrap(ix - 1, nx), xp = wrap(ix + 1, nx);
        const double v = m(ix, iy);
        if (v > m(xm, ym) && v > m(ix, ym) && v > m(xp, ym) && v > m(xm, iy) && v > m(xp, iy) &&
            v > m(xm, yp) && v > m(ix, yp) && v > m(xp, yp))
          part[c].push_back(v / h0);
      }
    }
  });
  for (const auto& p : part) s.xi.insert(s.xi.end(), p.begin(), p.end());
  s.count = s.xi.size();
  const double area = (nx - 2 * lo) * m.dx * (ny - 2 * lo) * m.dy;
  s.density = s.count / area;
  if (s.count > 0) {
    double sum = 0, sum2 = 0;
    for (double x : s.xi) sum += x;
    s.mean = sum / s.count;
    for (double x : s.xi) sum2 += (x - s.mean) * (x - s.mean);
    s.variance = s.count > 1 ? sum2 / (s.count - 1) : 0.0;
  }
  return s;
}

}  // namespace wr
