#include "lib/flow/contact_gap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lib/core/errors.hpp"

namespace wr {

HeightMap contact_gap_map(const HeightMap& like, const BigVector& pressure, const BigVector& gap) {
  if (pressure.size() != like.size() || gap.size() != like.size())
    throw std::invalid_argument("contact_gap_map: pressure and gap must have one value per grid point");
  HeightMap g(like.nx, like.ny, like.dx, like.dy);
  g.periodic = like.periodic;
  for (std::size_t k = 0; k < g.size(); ++k) g.h[k] = pressure[k] > 0 ? 0.0 : std::max(gap[k], 0.0);
  return g;
}

HeightMap rigid_flat_gap(const HeightMap& surface, double level) {
  HeightMap g(surface.nx, surface.ny, surface.dx, surface.dy);
  g.periodic = surface.periodic;
  for (std::size_t k = 0; k < g.size(); ++k) g.h[k] = std::max(level - surface.h[k], 0.0);
  return g;
}

double level_at_contact_fraction(const HeightMap& surface, double fraction) {
  if (!(fraction > 0 && fraction < 1)) throw InputError("--contact-fraction", "must be in (0, 1)");
  const std::size_t n = surface.size();
  if (n == 0) throw InputError("--contact-fraction", "the surface is empty");
  const auto k = std::max<std::size_t>(1, std::min(n, static_cast<std::size_t>(std::llround(fraction * double(n)))));
  std::vector<double> h(surface.h.begin(), surface.h.end());
  // The k-th highest height: the k highest points touch (h >= level), the others have gap > 0.
  std::nth_element(h.begin(), h.begin() + std::ptrdiff_t(k - 1), h.end(), std::greater<>());
  return h[k - 1];
}

namespace {
double mean_gap_at(const HeightMap& s, double level) {
  double sum = 0;
  for (std::size_t k = 0; k < s.size(); ++k) sum += std::max(level - s.h[k], 0.0);
  return sum / double(s.size());
}
}  // namespace

double level_at_mean_separation(const HeightMap& surface, double separation) {
  if (!(separation > 0 && std::isfinite(separation))) throw InputError("--separation", "must be a length > 0 in m");
  if (surface.size() == 0) throw InputError("--separation", "the surface is empty");
  const auto [lo_it, hi_it] = std::minmax_element(surface.h.begin(), surface.h.end());
  // The mean gap grows monotonically with the level, from 0 at the lowest point.
  double lo = *lo_it, hi = *hi_it + separation;
  const double resolution = 1e-12 * std::max(*hi_it - *lo_it, separation);
  while (hi - lo > resolution) {
    const double mid = 0.5 * (lo + hi);
    (mean_gap_at(surface, mid) < separation ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double contact_fraction(const HeightMap& gap) {
  std::size_t closed = 0;
  for (std::size_t k = 0; k < gap.size(); ++k) closed += gap.h[k] == 0;
  return gap.size() ? double(closed) / double(gap.size()) : 0.0;
}

}  // namespace wr
