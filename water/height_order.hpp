#pragma once
// Cell indices in increasing height, ties by index: the activation order of every sweep in
// water/. Sorting (height, index) pairs in place is several times faster than sorting indices
// through a comparator that reads the heights at random.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace wr {

template <class Heights>
std::vector<std::uint32_t> cells_in_height_order(const Heights& h) {
  std::vector<std::pair<double, std::uint32_t>> key(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) key[i] = {h[i], static_cast<std::uint32_t>(i)};
  std::sort(key.begin(), key.end());
  std::vector<std::uint32_t> order(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) order[i] = key[i].second;
  return order;
}

}  // namespace wr
