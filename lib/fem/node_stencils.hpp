#pragma once
// The block's stiffness rows as a few shared stencils (issue 58, the product's kernel). On the
// graded brick mesh every layer is one brick repeated, so the row of K at a node (its 3 x 3
// blocks against the nodes around it, hanging-node interpolation included) depends only on the
// node's plane, its parity (i mod 2, j mod 2) against a coarser layer, and the block's edges.
// Here each owned node's row is assembled once, rows equal to the last bit share one class, and
// the product is y_n = sum_k B_ck x_(n + o_ck): about 27 blocks (43 beside a coarser layer),
// 243 multiply-adds per node against 576 per brick, vectorised over runs of nodes of one class.
//
// Layout: x and y are held component by component ("SoA"), plane by plane and row by row, so that
// a class is a run of consecutive positions along a row with the same offsets. Rows whose nodes
// alternate between two stencils (below a plane with hanging nodes) are split, their even node
// indices first, then their odd ones; x is held both split and unsplit, and each neighbour plane
// is read in the layout in which a run's neighbours are consecutive too. Each row extends a few
// cells past this rank's slab to hold the other ranks' nodes this rank's rows touch (ghosts),
// so the slab's edges need no class of their own.
// Contract: built for one rank of `g`'s partition; `layer_k` are the layers' 24 x 24 brick
// matrices (row-major, corners c = a + 2 b + 4 k as GradedMesh::corner). Units: those of
// `layer_k` (N/m). Throws std::logic_error if the mesh breaks the layout's assumptions.
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "lib/fem/graded_mesh.hpp"

namespace wr {

class NodeStencils {
 public:
  NodeStencils(const GradedMesh& g, int rank, const std::vector<std::array<double, 576>>& layer_k);

  // The other ranks' nodes that this rank's rows touch: their values come after the owned ones.
  const std::vector<std::int32_t>& ghost_ids() const { return ghost_ids_; }
  // The owned nodes (id - own_begin) that other ranks may hold as ghosts: those within the
  // layout's margin of the slab's edges.
  const std::vector<std::int32_t>& edge_nodes() const { return edge_nodes_; }
  // The product in steps, so that an operator built on K can change a few nodes' values on the
  // way in (MatrixFreeFramed): load the owned values (3 per node, node order) and the ghosts'
  // (3 per ghost, ghost_ids() order), overwrite single nodes, then yo (3 x owned) = K x. The
  // loaded values live in internal buffers: not thread-safe, one product at a time.
  // single: in float (the multigrid's smoothers: a preconditioner needs no more, and the product
  // takes half the time), else in double.
  void load_owned(const double* xo, bool single = false) const;
  void load_ghosts(const double* xg, bool single = false) const;
  void set_node(std::int32_t k, const double* v, bool single = false) const {  // owned node k's 3 values
    if (single) put(xs_single_, k, v);  // after load_owned(.., true), which makes the float buffers
    else put(xs_, k, v);
  }
  void product(double* yo, bool single = false) const;
  // The 3 x 3 diagonal block (row-major) of owned node `k` (id - own_begin).
  const double* self_block(std::int32_t k) const { return &self_[9 * std::size_t(k)]; }
  std::size_t classes() const { return class_begin_.size() - 1; }
  std::size_t runs() const { return run_start_.size(); }
  std::size_t memory_bytes() const;

 private:
  struct PlaneLayout;
  struct Layout;
  struct Entry;
  Layout lay_out(const GradedMesh& g, int rank);  // the layouts, position_, x_natural_, x_split_, edge_nodes_
  void assemble(const GradedMesh& g, int rank, const Layout& layout, const std::vector<std::array<double, 576>>& layer_k);
  void join_row(std::int32_t here, std::int32_t node, std::vector<Entry>& row,
                std::unordered_map<std::string, std::int32_t>& class_index);
  static void add_block(std::vector<Entry>& row, std::int32_t pos, double w, const double* k, int a, int c);
  template <class T>
  void put(std::vector<T>& xs, std::int32_t k, const double* v) const {
    const std::size_t stride = std::size_t(positions_), a = std::size_t(x_natural_[std::size_t(k)]), b = std::size_t(x_split_[std::size_t(k)]);
    for (int c = 0; c < 3; ++c) xs[std::size_t(c) * stride + a] = xs[std::size_t(c) * stride + b] = T(v[c]);
  }
  void prepare_single() const;
  template <class T>
  void product_in(const std::vector<T>& block, const std::vector<T>& xs, std::vector<T>& ys, double* yo) const;

  std::int32_t owned_ = 0;
  std::vector<std::int32_t> ghost_ids_, edge_nodes_;
  std::vector<std::int32_t> position_;             // owned node -> its row's position (y)
  std::vector<std::int32_t> x_natural_, x_split_;  // local node (owned, then ghosts) -> x's positions
  // Classes: the blocks of entries class_begin_[c] ... class_begin_[c + 1] (9 doubles each).
  std::vector<std::uint32_t> class_begin_;
  std::vector<double> block_;
  // Runs of consecutive owned positions of one class and one set of offsets (a row's offsets to
  // the plane below or above change from row to row where the planes' levels differ; along a
  // run they do not): run r's offsets follow run r - 1's in run_offset_.
  std::vector<std::int32_t> run_start_, run_count_, run_class_, run_offset_;
  std::vector<double> self_;            // 9 per owned node
  mutable std::vector<double> xs_, ys_;  // 3 x positions each, component-major
  mutable std::vector<float> block_single_, xs_single_, ys_single_;  // made on first use
  std::int32_t positions_ = 0;
};

}  // namespace wr
