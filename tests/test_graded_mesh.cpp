// The graded block mesh: hanging nodes interpolate linear fields exactly, every independent
// node has one owner, and the counts add up.
#include <gtest/gtest.h>

#include <set>

#include "lib/fem/graded_mesh.hpp"

namespace wr {
namespace {

GradedMeshSpec spec_600_class() {
  GradedMeshSpec s;
  s.lx = s.ly = s.lz = 0.03;
  s.nx = s.ny = 48;  // 48 -> 24 -> 12 -> 6 -> (3: odd, stop)
  s.min_cells = 2;
  return s;
}

TEST(GradedMesh, CoarsensWhileEvenAndKeepsTheFaceLattice) {
  const GradedMesh m(spec_600_class(), 1);
  EXPECT_EQ(m.coarsenings(), 4);  // 48, 24, 12, 6, 3
  EXPECT_EQ(m.planes().front().level, 0);
  EXPECT_DOUBLE_EQ(m.planes().back().z, 0.03);
  EXPECT_NEAR(m.planes()[1].z, 0.03 / 48, 1e-15);  // cubes at the face
  for (int e = 1; e < m.layers(); ++e) {
    EXPECT_GE(m.layer_level(e), m.layer_level(e - 1));
    EXPECT_LE(m.layer_level(e), m.layer_level(e - 1) + 1);  // 2:1 balance
    EXPECT_GT(m.planes()[e + 1].z, m.planes()[e].z);
  }
  // Independent nodes = mesh points minus hanging ones (3/4 of an interface plane's points,
  // counted here directly).
  std::int64_t hanging = 0;
  for (const auto& p : m.planes())
    for (auto id : p.id) hanging += id < 0;
  EXPECT_GT(hanging, 0);
  EXPECT_EQ(m.nodes() + hanging, m.mesh_points());
}

TEST(GradedMesh, HangingNodesInterpolateLinearFieldsExactly) {
  const GradedMesh m(spec_600_class(), 1);
  auto f = [](const Vec3& x) { return 2.0 + 3.0 * x.x - 5.0 * x.y + 7.0 * x.z; };
  std::vector<Vec3> pos(std::size_t(m.nodes()));
  for (int p = 0; p < int(m.planes().size()); ++p) {
    const int l = m.planes()[p].level;
    for (int j = 0; j <= m.cells_y(l); ++j)
      for (int i = 0; i <= m.cells_x(l); ++i)
        if (m.node(p, i, j) >= 0) pos[std::size_t(m.node(p, i, j))] = m.position(p, i, j);
  }
  std::vector<GradedMesh::Parent> ps;
  int checked = 0;
  for (int p = 0; p < int(m.planes().size()); ++p) {
    const int l = m.planes()[p].level;
    for (int j = 0; j <= m.cells_y(l); ++j)
      for (int i = 0; i <= m.cells_x(l); ++i) {
        ps.clear();
        m.parents(p, i, j, ps);
        double v = 0, wsum = 0;
        for (const auto& q : ps) {
          ASSERT_GE(q.id, 0);
          v += q.weight * f(pos[std::size_t(q.id)]);
          wsum += q.weight;
        }
        EXPECT_NEAR(wsum, 1.0, 1e-15);
        EXPECT_NEAR(v, f(m.position(p, i, j)), 1e-12);
        checked += ps.size() > 1;
      }
  }
  EXPECT_GT(checked, 0);
  // Brick corners: every corner is a mesh point of the brick's own top or bottom plane.
  for (int e = 0; e < m.layers(); ++e) {
    int p, pi, pj;
    m.corner(e, m.cells_x(m.layer_level(e)) - 1, 0, 7, p, pi, pj);
    EXPECT_EQ(p, e + 1);
    EXPECT_EQ(m.position(p, pi, pj).x, 0.03);
  }
}

TEST(GradedMesh, RanksOwnContiguousIdsAndEqualFaceShares) {
  for (int ranks : {1, 2, 3}) {
    const GradedMesh m(spec_600_class(), ranks);
    std::set<std::int32_t> seen;
    for (int r = 0; r < ranks; ++r) {
      for (int p = 0; p < int(m.planes().size()); ++p) {
        const int l = m.planes()[p].level;
        for (int j = 0; j <= m.cells_y(l); ++j)
          for (int i = m.owned_i_begin(r, l); i < m.owned_i_end(r, l); ++i) {
            const auto id = m.node(p, i, j);
            if (id < 0) continue;
            EXPECT_GE(id, m.owned_begin(r));
            EXPECT_LT(id, m.owned_end(r));
            EXPECT_TRUE(seen.insert(id).second);
          }
      }
    }
    EXPECT_EQ(std::int64_t(seen.size()), m.nodes());
    EXPECT_EQ(m.owned_end(ranks - 1), m.nodes());
  }
  GradedMeshSpec s = spec_600_class();
  s.nx = 6;
  s.max_coarsenings = 0;
  EXPECT_THROW(GradedMesh(s, 7), std::invalid_argument);  // more ranks than coarse cells
}

}  // namespace
}  // namespace wr
