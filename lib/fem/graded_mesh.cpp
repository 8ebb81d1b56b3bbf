#include "lib/fem/graded_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wr {

GradedMesh::GradedMesh(const GradedMeshSpec& spec, int ranks) : spec_(spec) {
  if (!(spec.lx > 0 && spec.ly > 0 && spec.lz > 0)) throw std::invalid_argument("block sizes must be > 0");
  if (spec.nx < 1 || spec.ny < 1) throw std::invalid_argument("the face needs at least one cell per side");
  if (spec.layers_per_level < 1) throw std::invalid_argument("layers per level must be >= 1");
  if (!(spec.growth >= 1) || !(spec.max_aspect >= 1)) throw std::invalid_argument("growth and aspect must be >= 1");
  if (ranks < 1) throw std::invalid_argument("ranks must be >= 1");

  // Layers: cubes at the face spacing, doubling in-plane every `layers_per_level` layers while
  // there is room, then the coarsest level thickens geometrically up to the top.
  auto spacing = [&](int l) { return std::sqrt(hx(l) * hy(l)); };
  auto can_coarsen = [&](int l) {
    return l < spec.max_coarsenings && cells_x(l) % 2 == 0 && cells_y(l) % 2 == 0 &&
           cells_x(l) / 2 >= spec.min_cells && cells_y(l) / 2 >= spec.min_cells;
  };
  planes_.push_back(Plane{0, 0.0, false, {}});
  auto add_layer = [&](int level, double t) {
    if (planes_.back().level < level) planes_.back().interface = true;
    planes_.push_back(Plane{level, planes_.back().z + t, false, {}});
  };
  int level = 0;
  while (can_coarsen(level)) {
    // The fine layers and at least one layer of the next level must fit below the top.
    const double need = spec.layers_per_level * spacing(level) + spacing(level + 1);
    if (planes_.back().z + need > spec.lz) break;
    for (int k = 0; k < spec.layers_per_level; ++k) add_layer(level, spacing(level));
    ++level;
  }
  coarsenings_ = level;
  double t = spacing(level);
  const double t_max = spec.max_aspect * spacing(level);
  for (;;) {
    const double left = spec.lz - planes_.back().z;
    if (left < 1.5 * t) {  // the last layer takes what is left (between 0.5 t and 1.5 t)
      add_layer(level, left);
      break;
    }
    add_layer(level, t);
    t = std::min(t * spec.growth, t_max);
  }
  planes_.back().z = spec.lz;

  // Slabs along the coarsest cell boundaries.
  const int coarse = cells_x(coarsenings_);
  if (coarse < ranks)
    throw std::invalid_argument("the coarsest mesh level has " + std::to_string(coarse) + " cells across, fewer than the " +
                                std::to_string(ranks) + " ranks");
  for (int r = 0; r <= ranks; ++r) cut_.push_back(int((std::int64_t(r) * coarse / ranks) << coarsenings_));

  for (Plane& p : planes_) p.id.assign(std::size_t(cells_x(p.level) + 1) * (cells_y(p.level) + 1), -1);
  std::int64_t next = 0;
  for (int r = 0; r < ranks; ++r) {
    offset_.push_back(std::int32_t(next));
    for (Plane& p : planes_) {
      const int nxp = cells_x(p.level), nyp = cells_y(p.level);
      for (int j = 0; j <= nyp; ++j)
        for (int i = owned_i_begin(r, p.level); i < owned_i_end(r, p.level); ++i) {
          if (p.interface && (i % 2 || j % 2)) continue;
          p.id[std::size_t(j) * (nxp + 1) + i] = std::int32_t(next++);
        }
    }
  }
  offset_.push_back(std::int32_t(next));
  if (next >= (std::int64_t(1) << 31) / 3) throw std::invalid_argument("mesh too large for 32-bit PETSc indices");
  nodes_ = next;
  for (const Plane& p : planes_) points_ += std::int64_t(p.id.size());
}

int GradedMesh::owned_i_end(int rank, int level) const {
  return rank + 2 == int(cut_.size()) ? cells_x(level) + 1 : cut_[rank + 1] >> level;
}

std::int64_t GradedMesh::elements() const {
  std::int64_t n = 0;
  for (int e = 0; e < layers(); ++e) n += std::int64_t(cells_x(layer_level(e))) * cells_y(layer_level(e));
  return n;
}

void GradedMesh::parents(int plane, int i, int j, std::vector<Parent>& out) const {
  const std::int32_t id = node(plane, i, j);
  if (id >= 0) {
    out.push_back({id, 1.0, i, j});
    return;
  }
  const int i0 = i % 2 ? i - 1 : i, i1 = i % 2 ? i + 1 : i;
  const int j0 = j % 2 ? j - 1 : j, j1 = j % 2 ? j + 1 : j;
  const double w = (i0 == i1 ? 1.0 : 0.5) * (j0 == j1 ? 1.0 : 0.5);
  for (int jj : {j0, j1}) {
    for (int ii : {i0, i1}) {
      out.push_back({node(plane, ii, jj), w, ii, jj});
      if (i0 == i1) break;
    }
    if (j0 == j1) break;
  }
}

void GradedMesh::interpolation_at(const Vec3& p, std::vector<Parent>& out) const {
  out.clear();
  const double z = std::clamp(p.z, planes_.front().z, planes_.back().z);
  // The layer whose [z_e, z_e+1] holds z (the lowest one on a plane between two).
  auto above = std::upper_bound(planes_.begin() + 1, planes_.end(), z, [](double v, const Plane& q) { return v <= q.z; });
  const int e = std::min(int(above - planes_.begin()) - 1, layers() - 1);
  const int l = layer_level(e);
  auto cell = [](double x, double h, int n, double& t) {
    const int i = std::clamp(int(std::floor(x / h)), 0, n - 1);
    t = std::clamp(x / h - i, 0.0, 1.0);
    return i;
  };
  double tx, ty;
  const int i = cell(p.x, hx(l), cells_x(l), tx), j = cell(p.y, hy(l), cells_y(l), ty);
  const double tz = std::clamp((z - planes_[e].z) / (planes_[e + 1].z - planes_[e].z), 0.0, 1.0);
  std::vector<Parent> ps;
  for (int c = 0; c < 8; ++c) {
    const double w = (c & 1 ? tx : 1 - tx) * (c & 2 ? ty : 1 - ty) * (c & 4 ? tz : 1 - tz);
    if (w < 1e-14) continue;
    int q, qi, qj;
    corner(e, i, j, c, q, qi, qj);
    ps.clear();
    parents(q, qi, qj, ps);
    for (const Parent& a : ps) {
      auto it = std::find_if(out.begin(), out.end(), [&](const Parent& b) { return b.id == a.id; });
      if (it == out.end()) out.push_back({a.id, w * a.weight});
      else it->weight += w * a.weight;
    }
  }
}

void GradedMesh::corner(int layer, int i, int j, int c, int& plane, int& pi, int& pj) const {
  const int l = layer_level(layer);
  plane = layer + (c >> 2);
  const int shift = l - planes_[plane].level;
  pi = (i + (c & 1)) << shift;
  pj = (j + ((c >> 1) & 1)) << shift;
}

}  // namespace wr
