#include "water/fill_spill_merge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/core/errors.hpp"

namespace wr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One rain depth on one hierarchy. Bookkeeping is per node and local: own[N] is the water
// in N's own lake (above its creation level, only once both children are full; all of a
// leaf's water), own_cap[N] its room up to N's spill level. A node is full when its own lake
// and (for a merge node) both children are full; fullness only ever switches on. Rain is
// poured leaf by leaf: it fills the entry node, overflows to the sibling over the saddle (or
// to infinity in drained mode), and rises into the parent's lake when both sides are full.
// The walk stops as soon as the water is absorbed, so no subtree totals need updating, and
// the final state does not depend on the pouring order.
class Filler {
 public:
  Filler(const DepressionHierarchy& dh, WaterMode mode) : dh_(dh), nd_(dh.nodes()), mode_(mode) {
    const std::size_t n = nd_.size();
    cap_.assign(n, kInf);
    own_cap_.assign(n, kInf);
    drains_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const DepressionNode& N = nd_[i];
      const double parent_level = N.parent >= 0 ? nd_[N.parent].level : kInf;
      if (mode_ == WaterMode::stagnant) {
        cap_[i] = std::isfinite(parent_level) ? dh_.volume(int(i), parent_level) : kInf;
      } else {
        const bool ocean = N.ocean_at_birth || N.wraps();
        drains_[i] = ocean || (N.parent >= 0 && nd_[N.parent].ocean_at_birth);
        if (N.ocean_at_birth)
          cap_[i] = N.is_leaf() ? 0.0 : cap_[N.child[0]] + cap_[N.child[1]];  // no lake of its own
        else if (N.wraps())
          cap_[i] = dh_.volume(int(i), N.wrap);
        else if (std::isfinite(parent_level))
          cap_[i] = dh_.volume(int(i), parent_level);
      }
      own_cap_[i] = N.is_leaf() ? cap_[i] : cap_[i] - cap_[N.child[0]] - cap_[N.child[1]];
      if (!(own_cap_[i] > 0)) own_cap_[i] = std::isinf(cap_[i]) ? kInf : 0.0;
    }
  }

  WaterState run(double d) {
    const std::size_t n = nd_.size();
    own_.assign(n, 0.0);
    full_.assign(n, 0);
    skip_.assign(n, -1);
    // Nodes with no room of their own are full as soon as their children are (children first).
    for (std::size_t i = 0; i < n; ++i) full_[i] = own_cap_[i] <= 0 && children_full(int(i));
    drained_ = 0;
    std::vector<double> rain(n, 0.0);
    for (std::uint32_t c = 0; c < dh_.cells(); ++c) {
      const int r = dh_.rain_node(c);
      if (r < 0)
        drained_ += d;  // rain on a cell that drains off the map
      else
        rain[r] += d;
    }
    const int root = int(n) - 1;
    for (std::size_t i = 0; i < n; ++i)
      if (rain[i] > 0) {
        const double left = pour(int(i), rain[i], root);
        drained_ += left;  // beyond the root: only in drained mode (the root reaches infinity)
      }
    return levels(d);
  }

 private:
  bool full(int i) const { return full_[i] != 0; }

  bool children_full(int i) const { return nd_[i].is_leaf() || (full_[nd_[i].child[0]] && full_[nd_[i].child[1]]); }

  // Node i just became full: so may its ancestors whose own room is already used up.
  void mark_full(int i) {
    full_[i] = 1;
    for (int a = nd_[i].parent; a >= 0 && !full_[a] && own_[a] >= own_cap_[a] && children_full(a); a = nd_[a].parent)
      full_[a] = 1;
  }

  // The last node of N's chain of skips (path halving keeps chains short).
  int follow_skips(int N) {
    while (skip_[N] >= 0) {
      const int next = skip_[N];
      if (skip_[next] >= 0) skip_[N] = skip_[next];
      N = next;
    }
    return N;
  }

  // Adds up to E to node i's own lake; returns the amount taken.
  double take(int i, double E) {
    const double room = own_cap_[i] - own_[i];
    if (!(room > 0)) return 0.0;
    if (E >= room) {
      own_[i] = own_cap_[i];
      if (children_full(i)) mark_full(i);
      return room;
    }
    own_[i] += E;
    return E;
  }

  // Pours E into the subtree of `top`, entering at node e; returns what does not fit.
  double pour(int e, double E, int top) {
    int N = e;
    // Water entering a merge node whose sides are not both full runs down into a side.
    while (!children_full(N)) N = full(nd_[N].child[0]) ? nd_[N].child[1] : nd_[N].child[0];
    E -= take(N, E);
    while (E > 0 && N != top) {
      if (mode_ == WaterMode::drained && drains_[N]) {
        drained_ += E;
        return 0.0;
      }
      // Overflow passes unchanged through chains of full nodes with full siblings: jump.
      // Ancestors have larger indices, so a jump beyond `top` means top is full: return there.
      if (skip_[N] >= 0) {
        const int to = follow_skips(N);
        if (to > top) return E;
        N = to;
        continue;
      }
      const int A = nd_[N].parent;
      const int side = nd_[A].child[0] == N ? 0 : 1;
      const int S = nd_[A].child[1 - side];
      if (!full(S)) E = pour(nd_[A].entry[side] >= 0 ? nd_[A].entry[side] : S, E, S);
      if (E > 0) E -= take(A, E);
      if (full(S) && full(A) && !(mode_ == WaterMode::drained && drains_[N])) skip_[N] = A;
      N = A;
    }
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
      if (!children_full(int(j))) continue;
      const double held = own_[j] + (N.is_leaf() ? 0.0 : cap_[N.child[0]] + cap_[N.child[1]]);
      double z = dh_.level_for_volume(int(j), held);
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
  std::vector<double> cap_, own_cap_, own_;
  std::vector<char> drains_, full_;
  std::vector<int> skip_;  // overflow from N passes unchanged to skip_[N]
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
