#include "water/fill_spill_merge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/core/errors.hpp"

namespace wr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One rain depth on one hierarchy: holdings H[N] (water in N's subtree, m x cells) and the
// capacities of the mode.
class Filler {
 public:
  Filler(const DepressionHierarchy& dh, WaterMode mode) : dh_(dh), nd_(dh.nodes()), mode_(mode) {
    const std::size_t n = nd_.size();
    cap_.assign(n, kInf);
    drains_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const DepressionNode& N = nd_[i];
      const double parent_level = N.parent >= 0 ? nd_[N.parent].level : kInf;
      if (mode_ == WaterMode::stagnant) {
        cap_[i] = std::isfinite(parent_level) ? dh_.volume(int(i), parent_level) : kInf;
        continue;
      }
      const bool ocean = N.ocean_at_birth || N.wraps();
      drains_[i] = ocean || (N.parent >= 0 && nd_[N.parent].ocean_at_birth);
      if (N.ocean_at_birth)
        cap_[i] = 0;  // never holds a lake of its own: whatever reaches its level drains
      else if (N.wraps())
        cap_[i] = dh_.volume(int(i), N.wrap);
      else if (std::isfinite(parent_level))
        cap_[i] = dh_.volume(int(i), parent_level);
    }
  }

  WaterState run(double d) {
    const std::size_t n = nd_.size();
    H_.assign(n, 0.0);
    own_lake_.assign(n, 0.0);
    drained_ = 0;
    std::vector<double> rain(n, 0.0);
    for (std::uint32_t c = 0; c < dh_.cells(); ++c) {
      const int r = dh_.rain_node(c);
      if (r < 0)
        drained_ += d;  // rain on a cell that drains off the map
      else
        rain[r] += d;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const DepressionNode& N = nd_[i];
      if (N.is_leaf()) {
        H_[i] = rain[i];
        continue;
      }
      double E[2];
      for (int k = 0; k < 2; ++k) E[k] = close(N.child[k]);
      for (int k = 0; k < 2; ++k) {
        const int other = N.child[1 - k];
        if (E[k] > 0 && H_[other] < cap_[other]) E[k] = pour(N.entry[k] >= 0 ? N.entry[k] : other, E[k], other);
      }
      H_[i] = H_[N.child[0]] + H_[N.child[1]];
      const double extra = E[0] + E[1] + rain[i];
      if (mode_ == WaterMode::drained && N.ocean_at_birth)
        drained_ += extra;
      else
        add_own(int(i), extra);
    }
    const int root = int(n) - 1;
    if (mode_ == WaterMode::drained && !nd_[root].ocean_at_birth && H_[root] > cap_[root]) {
      drained_ += H_[root] - cap_[root];
      H_[root] = cap_[root];
    }
    return levels(d);
  }

 private:
  bool full(int i) const { return H_[i] >= cap_[i]; }

  void add_own(int i, double v) {
    H_[i] += v;
    own_lake_[i] += v;
  }

  // Caps child c at its spill level; returns the excess that flows over the saddle (0 when it
  // leaves through infinity in drained mode).
  double close(int c) {
    if (mode_ == WaterMode::drained && nd_[c].ocean_at_birth) return 0.0;
    const double excess = H_[c] - cap_[c];
    if (excess <= 0) return 0.0;
    H_[c] = cap_[c];
    if (mode_ == WaterMode::drained && drains_[c]) {
      drained_ += excess;
      return 0.0;
    }
    return excess;
  }

  // Pours E into the subtree of `top`, entering at node e; returns what does not fit.
  double pour(int e, double E, int top) {
    int N = e;
    // Enter at a node whose own lake exists (descend past merge nodes with non-full children).
    while (!nd_[N].is_leaf() && !(full(nd_[N].child[0]) && full(nd_[N].child[1])))
      N = full(nd_[N].child[0]) ? nd_[N].child[1] : nd_[N].child[0];
    double absorbed = take(N, E);
    E -= absorbed;
    while (N != top) {
      const int A = nd_[N].parent;
      const int side = nd_[A].child[0] == N ? 0 : 1;
      const int S = nd_[A].child[1 - side];
      H_[A] += absorbed;
      double added = 0;
      if (E > 0) {
        if (mode_ == WaterMode::drained && drains_[N]) {
          drained_ += E;
          E = 0;
        } else {
          if (!full(S)) {
            const double before = E;
            E = pour(nd_[A].entry[side] >= 0 ? nd_[A].entry[side] : S, E, S);
            added += before - E;
            H_[A] += before - E;
          }
          if (E > 0) {
            const double t = take(A, E);
            E -= t;
            added += t;  // take() already added to H_[A]
          }
        }
      }
      absorbed += added;
      N = A;
    }
    return E;
  }

  // Adds up to E to node i's own lake, limited by its capacity; returns the amount taken.
  double take(int i, double E) {
    const double room = cap_[i] - H_[i];
    if (room <= 0) return 0.0;
    if (E >= room) {
      own_lake_[i] += room;
      H_[i] = cap_[i];
      return room;
    }
    add_own(i, E);
    return E;
  }

  WaterState levels(double d) {
    const std::size_t n = nd_.size();
    std::vector<double> lake(n, -kInf);
    for (std::size_t j = n; j-- > 0;) {
      const DepressionNode& N = nd_[j];
      if (N.parent >= 0 && lake[N.parent] > -kInf) {
        lake[j] = lake[N.parent];
        continue;
      }
      if (mode_ == WaterMode::drained && N.ocean_at_birth) continue;
      const bool has_lake = N.is_leaf() || (full(N.child[0]) && full(N.child[1]));
      if (!has_lake) continue;
      double z = dh_.level_for_volume(int(j), std::min(H_[j], cap_[j]));
      if (mode_ == WaterMode::drained && N.wraps()) z = std::min(z, N.wrap);
      if (N.parent >= 0) z = std::min(z, nd_[N.parent].level);
      lake[j] = z;
    }
    WaterState w;
    w.rain_depth = d;
    w.level.resize(dh_.cells());
    for (std::uint32_t c = 0; c < dh_.cells(); ++c) {
      const int o = dh_.owner(c);
      const double hc = dh_.height(c);
      w.level[c] = lake[o] > hc ? lake[o] : hc;
    }
    w.drained_volume = drained_ / double(dh_.cells());
    return w;
  }

  const DepressionHierarchy& dh_;
  const std::vector<DepressionNode>& nd_;
  WaterMode mode_;
  std::vector<double> cap_, H_, own_lake_;
  std::vector<char> drains_;
  double drained_ = 0;
};

}  // namespace

void summarize_water(const GridTopology& topo, const std::vector<double>& ground, WaterState& w) {
  std::size_t wet = 0;
  double sum = 0, mx = 0;
  for (std::size_t c = 0; c < ground.size(); ++c) {
    const double depth = w.level[c] - ground[c];
    if (depth > 0) {
      ++wet;
      sum += depth;
      mx = std::max(mx, depth);
    }
  }
  const double n = double(ground.size());
  w.coverage = wet / n;
  w.stored_volume = sum / n;
  w.mean_depth = wet ? sum / wet : 0.0;
  w.max_depth = mx;
  // Lakes: connected wet regions (breadth-first labelling).
  std::vector<char> seen(ground.size(), 0);
  std::vector<std::uint32_t> stack;
  w.lakes = 0;
  for (std::size_t c0 = 0; c0 < ground.size(); ++c0) {
    if (seen[c0] || !(w.level[c0] > ground[c0])) continue;
    ++w.lakes;
    seen[c0] = 1;
    stack.assign(1, static_cast<std::uint32_t>(c0));
    while (!stack.empty()) {
      const std::uint32_t c = stack.back();
      stack.pop_back();
      for (int k = 0; k < topo.connectivity(); ++k) {
        const Neighbour nb = topo.neighbour(c % topo.nx(), c / topo.nx(), k);
        if (nb.outside || seen[nb.cell] || !(w.level[nb.cell] > ground[nb.cell])) continue;
        seen[nb.cell] = 1;
        stack.push_back(nb.cell);
      }
    }
  }
}

WaterState fill_spill_merge(const DepressionHierarchy& dh, double rain_depth, WaterMode mode) {
  if (!std::isfinite(rain_depth) || rain_depth < 0)
    throw InputError("--rain", "the rain depth must be a finite depth >= 0 m");
  Filler f(dh, mode);
  WaterState w = f.run(rain_depth);
  std::vector<double> ground(dh.cells());
  for (std::uint32_t c = 0; c < dh.cells(); ++c) ground[c] = dh.height(c);
  summarize_water(dh.topology(), ground, w);
  return w;
}

}  // namespace wr
