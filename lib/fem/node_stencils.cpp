#include "lib/fem/node_stencils.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace wr {
// Where each plane's nodes lie in the two layouts: rows j over [lo, hi) (the slab and its
// margin), each row either in its natural order or split, its even node indices first, then its
// odd ones (node index: i, or i / 2 on an interface plane, whose odd i hang).
struct NodeStencils::PlaneLayout {
  int lo = 0, hi = 0;
  std::vector<std::int32_t> natural, split;  // (j, i) -> position, -1 where no node
  std::size_t cell(int i, int j) const {
    if (i < lo || i >= hi) throw std::logic_error("node stencils: a neighbour lies beyond the slab's margin");
    return std::size_t(j) * std::size_t(hi - lo) + std::size_t(i - lo);
  }
};

// x is held in both layouts, y in one per plane: split where the plane above has hanging nodes
// (the stencils alternate with the node index's parity there), natural elsewhere. A run of nodes
// steps `advance` finest cells; each neighbour plane is read in the layout in which the neighbours
// step by one position too.
struct NodeStencils::Layout {
  std::vector<PlaneLayout> plane;
  std::vector<int> node_step, advance;  // in finest cells
  std::vector<char> split_rows;
  std::int32_t x_position(std::size_t from, std::size_t q, int i, int j) const {
    const PlaneLayout& L = plane[q];
    if (advance[from] == 2 * node_step[q]) return L.split[L.cell(i, j)];
    return L.natural[L.cell(i, j)];  // steps of one position, or else runs of one node
  }
};

struct NodeStencils::Entry {
  std::int32_t pos;
  double b[9];
};

namespace {

// Cells of margin around the slab in every plane's rows: a row reaches one brick out, a brick's
// hanging corners one cell further, and a layer above may be one level coarser (doubling both).
constexpr int kMargin = 8;
constexpr int kRowsPerChunk = 8;  // rows assembled at once: bounds the build's memory

// ys (component-major, positions) = the runs' stencils applied to xs. The run is cut in pieces of
// 256 positions that stay in L1 while every entry of the class streams over them; the loop over
// the piece is what the compiler vectorises. T: double, or float for the multigrid's smoothers
// (8 nodes per AVX2 instruction instead of 4, half the bytes).
#define WR_APPLY_RUNS_ARGS(T)                                                                                               \
  std::size_t runs, const std::int32_t *run_start, const std::int32_t *run_count, const std::int32_t *run_class,          \
      const std::uint32_t *class_begin, const std::int32_t *run_offset, const T *block, std::size_t stride,                \
      const T *__restrict xs, T *__restrict ys
template <class T>
inline __attribute__((always_inline)) void apply_runs_body(WR_APPLY_RUNS_ARGS(T)) {
  constexpr std::int32_t kPiece = 256;
  for (std::size_t r = 0; r < runs; ++r) {
    const std::uint32_t e0 = class_begin[run_class[r]], e1 = class_begin[run_class[r] + 1];
    const std::int32_t* offset = run_offset - e0;  // this run's offsets, indexed as its class's entries
    run_offset += e1 - e0;
    const std::int32_t end = run_start[r] + run_count[r];
    for (std::int32_t t0 = run_start[r]; t0 < end; t0 += kPiece) {
      const std::int32_t m = std::min(kPiece, end - t0);
      T* __restrict y0 = ys + t0;
      T* __restrict y1 = y0 + stride;
      T* __restrict y2 = y1 + stride;
      for (std::int32_t t = 0; t < m; ++t) y0[t] = y1[t] = y2[t] = 0;
      for (std::uint32_t e = e0; e < e1; ++e) {
        const T* b = block + 9 * std::size_t(e);
        const T b00 = b[0], b01 = b[1], b02 = b[2], b10 = b[3], b11 = b[4], b12 = b[5], b20 = b[6], b21 = b[7], b22 = b[8];
        const T* __restrict x0 = xs + (t0 + offset[e]);
        const T* __restrict x1 = x0 + stride;
        const T* __restrict x2 = x1 + stride;
        for (std::int32_t t = 0; t < m; ++t) {
          const T u = x0[t], v = x1[t], w = x2[t];
          y0[t] += b00 * u + b01 * v + b02 * w;
          y1[t] += b10 * u + b11 * v + b12 * w;
          y2[t] += b20 * u + b21 * v + b22 * w;
        }
      }
    }
  }
}

template <class T>
void apply_runs_portable(WR_APPLY_RUNS_ARGS(T)) {
  apply_runs_body<T>(runs, run_start, run_count, run_class, class_begin, run_offset, block, stride, xs, ys);
}

// The same with AVX2 and FMA, where the CPU has both (x86-64 only).
#if defined(__x86_64__)
template <class T>
__attribute__((target("avx2,fma"))) void apply_runs_avx2(WR_APPLY_RUNS_ARGS(T)) {
  apply_runs_body<T>(runs, run_start, run_count, run_class, class_begin, run_offset, block, stride, xs, ys);
}
#endif

template <class T>
using ApplyRuns = void (*)(WR_APPLY_RUNS_ARGS(T));
#undef WR_APPLY_RUNS_ARGS

template <class T>
ApplyRuns<T> pick_apply_runs() {
#if defined(__x86_64__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return &apply_runs_avx2<T>;
#endif
  return &apply_runs_portable<T>;
}

}  // namespace

NodeStencils::NodeStencils(const GradedMesh& g, int rank, const std::vector<std::array<double, 576>>& layer_k) {
  owned_ = g.owned_end(rank) - g.owned_begin(rank);
  const Layout layout = lay_out(g, rank);
  assemble(g, rank, layout, layer_k);
  xs_.assign(3 * std::size_t(positions_), 0.0);
  ys_.assign(3 * std::size_t(positions_), 0.0);
}

NodeStencils::Layout NodeStencils::lay_out(const GradedMesh& g, int rank) {
  const auto& planes = g.planes();
  const std::size_t n_planes = planes.size();
  Layout layout;
  layout.plane.resize(n_planes);
  layout.node_step.resize(n_planes);
  layout.advance.resize(n_planes);
  layout.split_rows.resize(n_planes);
  for (std::size_t p = 0; p < n_planes; ++p) {
    layout.node_step[p] = 1 << (planes[p].level + int(planes[p].interface));
    layout.split_rows[p] = p + 1 < n_planes && planes[p + 1].interface;
    layout.advance[p] = layout.node_step[p] << int(layout.split_rows[p]);
  }
  // The natural layouts of all planes, then the split ones.
  std::int32_t next = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t p = 0; p < n_planes; ++p) {
      const int l = planes[p].level, nx = g.cells_x(l), ny = g.cells_y(l), step = int(planes[p].interface) + 1;
      PlaneLayout& L = layout.plane[p];
      if (pass == 0) {
        L.lo = std::max(0, g.owned_i_begin(rank, l) - kMargin);
        L.hi = std::min(nx + 1, g.owned_i_end(rank, l) + kMargin);
        L.natural.assign(std::size_t(ny + 1) * std::size_t(L.hi - L.lo), -1);
        L.split = L.natural;
      }
      for (int j = 0; j <= ny; ++j)
        for (int parity = 0; parity < 1 + pass; ++parity)
          for (int i = L.lo; i < L.hi; ++i)
            if (g.node(int(p), i, j) >= 0 && (pass == 0 || (i / step) % 2 == parity))
              (pass == 0 ? L.natural : L.split)[L.cell(i, j)] = next++;
    }
  positions_ = next;
  // Where the owned nodes' rows and values go.
  const std::int32_t own_begin = g.owned_begin(rank);
  position_.assign(std::size_t(owned_), -1);
  x_natural_.assign(std::size_t(owned_), -1);
  x_split_.assign(std::size_t(owned_), -1);
  for (std::size_t p = 0; p < n_planes; ++p) {
    const int l = planes[p].level, ib = g.owned_i_begin(rank, l), ie = g.owned_i_end(rank, l);
    const PlaneLayout& L = layout.plane[p];
    for (int j = 0; j <= g.cells_y(l); ++j)
      for (int i = ib; i < ie; ++i) {
        const std::int32_t id = g.node(int(p), i, j);
        if (id < 0) continue;
        const std::size_t k = std::size_t(id - own_begin), c = L.cell(i, j);
        position_[k] = layout.split_rows[p] ? L.split[c] : L.natural[c];
        x_natural_[k] = L.natural[c];
        x_split_[k] = L.split[c];
        if ((i < ib + kMargin && ib > 0) || (i >= ie - kMargin && ie <= g.cells_x(l))) edge_nodes_.push_back(std::int32_t(k));
      }
  }
  return layout;
}

// The rows, a few plane rows at a time: every brick of the two layers beside the plane that can
// reach those rows adds C_a^T K_layer C_c to the rows of its corners' owned parents.
void NodeStencils::assemble(const GradedMesh& g, int rank, const Layout& layout,
                            const std::vector<std::array<double, 576>>& layer_k) {
  const std::int32_t own_begin = g.owned_begin(rank), own_end = g.owned_end(rank);
  std::unordered_map<std::int32_t, std::int32_t> ghost_slot;
  auto note_ghost = [&](std::int32_t id, std::size_t q, int i, int j) {
    if (id >= own_begin && id < own_end) return;
    if (ghost_slot.try_emplace(id, std::int32_t(ghost_ids_.size())).second) {
      ghost_ids_.push_back(id);
      const PlaneLayout& L = layout.plane[q];
      x_natural_.push_back(L.natural[L.cell(i, j)]);
      x_split_.push_back(L.split[L.cell(i, j)]);
    }
  };
  std::vector<std::int32_t> owned_of(std::size_t(positions_), -1);  // position -> owned node
  for (std::int32_t n = 0; n < owned_; ++n) owned_of[std::size_t(position_[std::size_t(n)])] = n;
  std::unordered_map<std::string, std::int32_t> class_index;
  class_begin_.push_back(0);
  self_.assign(9 * std::size_t(owned_), 0.0);
  std::size_t rows_done = 0;
  std::map<std::int32_t, std::vector<Entry>> rows;  // by position: the runs are formed in order
  std::vector<GradedMesh::Parent> ps[8];
  int corner_plane[8];
  const auto& planes = g.planes();
  for (int p = 0; p < int(planes.size()); ++p) {
    const int lp = planes[std::size_t(p)].level;
    for (int j0 = 0; j0 <= g.cells_y(lp); j0 += kRowsPerChunk) {
      const int j1 = std::min(g.cells_y(lp) + 1, j0 + kRowsPerChunk);
      rows.clear();
      for (int e = p - 1; e <= p; ++e) {
        if (e < 0 || e >= g.layers()) continue;
        const int l = g.layer_level(e), shift = l - lp;
        const double* k = layer_k[std::size_t(e)].data();
        const int bj0 = std::max(0, (std::max(0, j0 - 3) >> shift) - 1);
        const int bj1 = std::min(g.cells_y(l), ((j1 + 2) >> shift) + 2);
        const int bi0 = std::max(0, g.owned_i_begin(rank, l) - 2);
        const int bi1 = std::min(g.cells_x(l), g.owned_i_end(rank, l) + 2);
        for (int bj = bj0; bj < bj1; ++bj)
          for (int bi = bi0; bi < bi1; ++bi) {
            for (int c = 0; c < 8; ++c) {
              int pi, pj;
              g.corner(e, bi, bj, c, corner_plane[c], pi, pj);
              ps[c].clear();
              g.parents(corner_plane[c], pi, pj, ps[c]);
            }
            for (int a = 0; a < 8; ++a) {
              if (corner_plane[a] != p) continue;
              for (const auto& pa : ps[a]) {
                if (pa.id < own_begin || pa.id >= own_end || pa.j < j0 || pa.j >= j1) continue;
                std::vector<Entry>& row = rows[position_[std::size_t(pa.id - own_begin)]];
                for (int c = 0; c < 8; ++c)
                  for (const auto& pc : ps[c]) {
                    const std::size_t q = std::size_t(corner_plane[c]);
                    note_ghost(pc.id, q, pc.i, pc.j);
                    add_block(row, layout.x_position(std::size_t(p), q, pc.i, pc.j), pa.weight * pc.weight, k, a, c);
                  }
              }
            }
          }
      }
      for (auto& [here, row] : rows) join_row(here, owned_of[std::size_t(here)], row, class_index);
      rows_done += rows.size();
    }
  }
  if (rows_done != std::size_t(owned_)) throw std::logic_error("node stencils: an owned node has no row, or two");
}

// A finished row joins the class whose blocks it equals bit for bit, and the run before it where
// it continues that run: same class, same offsets, the next position.
void NodeStencils::join_row(std::int32_t here, std::int32_t node, std::vector<Entry>& row,
                            std::unordered_map<std::string, std::int32_t>& class_index) {
  std::sort(row.begin(), row.end(), [](const Entry& x, const Entry& y) { return x.pos < y.pos; });
  std::string key;
  std::vector<std::int32_t> offsets;
  for (const Entry& en : row) {
    key.append(reinterpret_cast<const char*>(en.b), sizeof en.b);
    offsets.push_back(en.pos - here);
    if (en.pos == here) std::copy(en.b, en.b + 9, &self_[9 * std::size_t(node)]);
  }
  const auto [it, added] = class_index.try_emplace(key, std::int32_t(class_begin_.size() - 1));
  if (added) {
    for (const Entry& en : row) block_.insert(block_.end(), en.b, en.b + 9);
    class_begin_.push_back(std::uint32_t(block_.size() / 9));
  }
  const bool continues = !run_start_.empty() && run_class_.back() == it->second && run_start_.back() + run_count_.back() == here &&
                         std::equal(offsets.begin(), offsets.end(), run_offset_.end() - std::ptrdiff_t(offsets.size()));
  if (continues) {
    ++run_count_.back();
    return;
  }
  run_start_.push_back(here);
  run_count_.push_back(1);
  run_class_.push_back(it->second);
  run_offset_.insert(run_offset_.end(), offsets.begin(), offsets.end());
}

void NodeStencils::add_block(std::vector<Entry>& row, std::int32_t pos, double w, const double* k, int a, int c) {
  auto it = std::find_if(row.begin(), row.end(), [&](const Entry& e) { return e.pos == pos; });
  if (it == row.end()) {
    row.push_back(Entry{pos, {}});
    it = row.end() - 1;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) it->b[3 * i + j] += w * k[(3 * a + i) * 24 + 3 * c + j];
}


std::size_t NodeStencils::memory_bytes() const {
  return (ghost_ids_.size() + edge_nodes_.size() + position_.size() + x_natural_.size() + x_split_.size() + run_offset_.size() + 3 * run_start_.size()) * sizeof(std::int32_t) +
         class_begin_.size() * sizeof(std::uint32_t) + (block_.size() + self_.size() + xs_.size() + ys_.size()) * sizeof(double) +
         (block_single_.size() + xs_single_.size() + ys_single_.size()) * sizeof(float);
}

void NodeStencils::prepare_single() const {
  if (!xs_single_.empty()) return;  // the float copies are made on first use only: memory
  block_single_.assign(block_.begin(), block_.end());
  xs_single_.assign(3 * std::size_t(positions_), 0.0f);
  ys_single_.assign(3 * std::size_t(positions_), 0.0f);
}

void NodeStencils::load_owned(const double* xo, bool single) const {
  if (single) {
    prepare_single();
    for (std::int32_t k = 0; k < owned_; ++k) put(xs_single_, k, xo + 3 * std::size_t(k));
    return;
  }
  for (std::int32_t k = 0; k < owned_; ++k) put(xs_, k, xo + 3 * std::size_t(k));
}

void NodeStencils::load_ghosts(const double* xg, bool single) const {
  if (single) prepare_single();
  for (std::size_t g = 0; g < ghost_ids_.size(); ++g) set_node(owned_ + std::int32_t(g), xg + 3 * g, single);
}

template <class T>
void NodeStencils::product_in(const std::vector<T>& block, const std::vector<T>& xs, std::vector<T>& ys, double* yo) const {
  const std::size_t stride = std::size_t(positions_);
  static const ApplyRuns<T> apply_runs = pick_apply_runs<T>();
  apply_runs(run_start_.size(), run_start_.data(), run_count_.data(), run_class_.data(), class_begin_.data(), run_offset_.data(),
             block.data(), stride, xs.data(), ys.data());
  for (std::int32_t k = 0; k < owned_; ++k) {
    const std::size_t q = std::size_t(position_[std::size_t(k)]);
    yo[3 * k] = double(ys[q]), yo[3 * k + 1] = double(ys[stride + q]), yo[3 * k + 2] = double(ys[2 * stride + q]);
  }
}

void NodeStencils::product(double* yo, bool single) const {
  if (single) {
    prepare_single();
    product_in(block_single_, xs_single_, ys_single_, yo);
    return;
  }
  product_in(block_, xs_, ys_, yo);
}

}  // namespace wr
