#include "lib/flow/free_clusters.hpp"

#include <algorithm>

namespace wr {

bool FreeClusters::any_x() const { return std::find(winds_x.begin(), winds_x.end(), true) != winds_x.end(); }
bool FreeClusters::any_y() const { return std::find(winds_y.begin(), winds_y.end(), true) != winds_y.end(); }

namespace {

// One step of the search: from cell (i, j) with offset (ox, oy) to its neighbour across a face;
// crossing the seam changes the offset by one period.
struct Step {
  std::size_t cell;
  std::int32_t ox, oy;
};

// The four face neighbours of (i, j), with their unwrap offsets relative to the cell's.
void neighbours(std::size_t i, std::size_t j, std::size_t nx, std::size_t ny, std::int32_t ox, std::int32_t oy,
                Step out[4]) {
  const bool east_seam = i + 1 == nx, west_seam = i == 0, north_seam = j + 1 == ny, south_seam = j == 0;
  out[0] = {j * nx + (east_seam ? 0 : i + 1), ox + (east_seam ? 1 : 0), oy};
  out[1] = {j * nx + (west_seam ? nx - 1 : i - 1), ox - (west_seam ? 1 : 0), oy};
  out[2] = {(north_seam ? 0 : j + 1) * nx + i, ox, oy + (north_seam ? 1 : 0)};
  out[3] = {(south_seam ? ny - 1 : j - 1) * nx + i, ox, oy - (south_seam ? 1 : 0)};
}

}  // namespace

FreeClusters label_free_clusters(const HeightMap& gap) {
  const std::size_t nx = gap.nx, ny = gap.ny, n = gap.size();
  FreeClusters c;
  c.label.assign(n, -1);
  std::vector<std::int32_t> ox(n, 0), oy(n, 0);
  std::vector<std::size_t> queue;
  queue.reserve(n);
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (!(gap.h[seed] > 0) || c.label[seed] >= 0) continue;
    const auto id = static_cast<std::int32_t>(c.winds_x.size());
    bool wx = false, wy = false;
    c.label[seed] = id;
    queue.clear();
    queue.push_back(seed);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t cell = queue[head];
      Step nb[4];
      neighbours(cell % nx, cell / nx, nx, ny, ox[cell], oy[cell], nb);
      for (const Step& s : nb) {
        if (!(gap.h[s.cell] > 0)) continue;
        if (c.label[s.cell] < 0) {
          c.label[s.cell] = id;
          ox[s.cell] = s.ox;
          oy[s.cell] = s.oy;
          queue.push_back(s.cell);
        } else {
          wx = wx || ox[s.cell] != s.ox;
          wy = wy || oy[s.cell] != s.oy;
        }
      }
    }
    c.free_cells += queue.size();
    c.winds_x.push_back(wx);
    c.winds_y.push_back(wy);
  }
  return c;
}

}  // namespace wr
