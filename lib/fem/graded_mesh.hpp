#pragma once
// The block's mesh: trilinear bricks graded towards the contact face z = 0, in-plane as well as
// in depth. The face lattice (spacing = obstacle spacing / refine) is kept for
// `layers_per_level` layers of cubes, then the in-plane spacing doubles ("2:1 balanced"
// octree-like layers), again and again while the cell counts stay even; the coarsest level
// fills the rest of the block with layers that thicken geometrically. Where a fine layer meets
// a coarse one, the fine nodes that are not coarse nodes are "hanging": they follow the
// coarse face's bilinear interpolation (weights 1/2 on an edge, 1/4 in a face centre), so the
// discretisation stays conforming. Only independent nodes carry degrees of freedom.
//
// Ownership (MPI): x-slabs cut along the coarsest level's cell boundaries, so that every rank
// owns the same share of the contact face (thesis sec. 4.3: the block is split in x and y;
// slabs in x are enough for a few ranks). Node ids are contiguous per rank, rank by rank.
// Units: metres.
#include <cstdint>
#include <vector>

#include "lib/core/vec3.hpp"

namespace wr {

struct GradedMeshSpec {
  double lx = 0.03, ly = 0.03, lz = 0.03;  // m
  int nx = 16, ny = 16;                     // face cells
  int layers_per_level = 2;                 // brick layers at each in-plane spacing before it doubles
  int max_coarsenings = 16;                 // in-plane doublings allowed (0: uniform in-plane)
  int min_cells = 4;                        // no doubling below this many cells per side
  double growth = 1.3;                      // layer thickness ratio in the coarsest level
  double max_aspect = 6.0;                  // cap on thickness / in-plane spacing there
};

class GradedMesh {
 public:
  // Throws std::invalid_argument for non-positive sizes or cell counts.
  GradedMesh(const GradedMeshSpec& spec, int ranks);

  struct Plane {
    int level = 0;        // in-plane grid: nx >> level by ny >> level cells
    double z = 0;         // m
    bool interface = false;  // odd (i, j) nodes hang (a coarser layer lies above)
    std::vector<std::int32_t> id;  // global node id per (i, j), row-major in j; -1 = hanging
  };
  struct Parent {
    std::int32_t id;
    double weight;
    int i = 0, j = 0;  // the node's place in its plane (set by parents(); not by interpolation_at())
  };

  const GradedMeshSpec& spec() const { return spec_; }
  int ranks() const { return int(cut_.size()) - 1; }
  int coarsenings() const { return coarsenings_; }
  int cells_x(int level) const { return spec_.nx >> level; }
  int cells_y(int level) const { return spec_.ny >> level; }
  double hx(int level) const { return spec_.lx / cells_x(level); }
  double hy(int level) const { return spec_.ly / cells_y(level); }

  const std::vector<Plane>& planes() const { return planes_; }
  int layers() const { return int(planes_.size()) - 1; }
  int layer_level(int layer) const { return planes_[layer + 1].level; }

  std::int64_t nodes() const { return nodes_; }          // independent nodes (3 dofs each)
  std::int64_t mesh_points() const { return points_; }   // including hanging nodes
  std::int64_t elements() const;
  // Node ids [begin, end) owned by `rank`.
  std::int32_t owned_begin(int rank) const { return offset_[rank]; }
  std::int32_t owned_end(int rank) const { return offset_[rank + 1]; }
  // Range of level-`level` node indices i owned by `rank`: [begin, end).
  int owned_i_begin(int rank, int level) const { return cut_[rank] >> level; }
  int owned_i_end(int rank, int level) const;

  std::int32_t node(int plane, int i, int j) const {
    const Plane& p = planes_[plane];
    return p.id[std::size_t(j) * (cells_x(p.level) + 1) + i];
  }
  Vec3 position(int plane, int i, int j) const {
    const Plane& p = planes_[plane];
    return {i * hx(p.level), j * hy(p.level), p.z};
  }
  // The independent nodes behind mesh point (plane, i, j): itself (weight 1) or its 2 or 4
  // coarse neighbours. Appends to `out`.
  void parents(int plane, int i, int j, std::vector<Parent>& out) const;
  // The trilinear interpolation of the mesh's field at point p (m; clamped into the block): the
  // independent nodes behind the brick that holds p, with their weights (summing to 1; entries
  // below 1e-14 dropped, ids distinct). Why: the transfers between two meshes of one block
  // (geometric multigrid, geometric_multigrid.hpp). Replaces `out`.
  void interpolation_at(const Vec3& p, std::vector<Parent>& out) const;
  // Corner c = a + 2 b + 4 k (a along x, b along y, k up) of brick (i, j) in `layer` as a
  // (plane, i, j) mesh point.
  void corner(int layer, int i, int j, int c, int& plane, int& pi, int& pj) const;

 private:
  GradedMeshSpec spec_;
  int coarsenings_ = 0;
  std::vector<Plane> planes_;
  std::vector<int> cut_;               // slab boundaries in face-cell units, ranks + 1 entries
  std::vector<std::int32_t> offset_;   // first node id per rank, ranks + 1 entries
  std::int64_t nodes_ = 0, points_ = 0;
};

}  // namespace wr
