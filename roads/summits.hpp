#pragma once
// Summits (local maxima) of a height map compared with Nayak's theory (thesis 3.1.3, 4.1.3).
//
// A summit is a sample strictly higher than its 8 neighbours (wrapping on periodic maps; the
// border row/column is skipped otherwise). Heights are normalised by h0: xi = h / h0 (eq. 3.61).
// Lattice summits are not continuous-surface summits: a sampled surface resolves only maxima
// wider than ~2 dx, which is one reason measured densities and means differ from theory.
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

struct SummitStats {
  std::size_t count = 0;
  double density = 0;   // 1/m^2
  double mean = 0;      // of xi
  double variance = 0;  // of xi
  std::vector<double> xi;  // normalised heights of every summit
};

// threads <= 0: all hardware threads; the summit list is in row order for any thread count.
SummitStats find_summits(const HeightMap& map, double h0, int threads = 0);

}  // namespace wr
