// Point clouds onto a grid (roads/point_cloud_grid.hpp): the linear interpolant on CGAL's
// Delaunay triangles against an analytic surface and its error bound, holes left as dropouts,
// and the text reader.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

#include "lib/core/errors.hpp"
#include "roads/point_cloud_grid.hpp"
#include "roads/surface_import.hpp"
#include "tests/cli_fixture.hpp"

namespace {

using wr::CloudPoint;
using wr::GriddedCloud;
using wr::PointCloudGridOptions;
constexpr double kPi = std::numbers::pi;

// f = A sin(a x) cos(b y): its Hessian's spectral norm is at most its Frobenius norm,
// A sqrt(a^4 + b^4 + 2 a^2 b^2) = A (a^2 + b^2) =: M.
struct Wave {
  double A = 2e-4, a = 2 * kPi / 6e-3, b = 2 * kPi / 9e-3;
  double operator()(double x, double y) const { return A * std::sin(a * x) * std::cos(b * y); }
  double hessian_bound() const { return A * (a * a + b * b); }
};

// Uniform random points on [0, L]^2, the four corners and sqrt(n) random points along each side
// (a scanner's frame is sampled like its inside, so the hull is the square without slivers along
// its edges); points within `hole` of the centre left out.
std::vector<CloudPoint> sample(const Wave& f, std::size_t n, double L, double hole = 0, unsigned seed = 11) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, L);
  std::vector<CloudPoint> pts;
  for (double x : {0.0, L})
    for (double y : {0.0, L}) pts.push_back({x, y, f(x, y)});
  for (std::size_t k = 0; k * k < n; ++k) {
    const double t = u(rng);
    for (const auto& [x, y] : {std::pair{t, 0.0}, {t, L}, {0.0, t}, {L, t}}) pts.push_back({x, y, f(x, y)});
  }
  while (pts.size() < n) {
    const double x = u(rng), y = u(rng);
    if (std::hypot(x - L / 2, y - L / 2) < hole) continue;
    pts.push_back({x, y, f(x, y)});
  }
  return pts;
}

// Bar 2: on every node, |interpolant - f| <= M D^2 / 6 (point_cloud_grid.hpp), D the longest
// edge of the triangles used; and the bound is tight enough to mean something (well under A).
TEST(PointCloud, LinearInterpolationStaysWithinItsErrorBound) {
  const Wave f;
  const double L = 0.02;
  PointCloudGridOptions opt;
  opt.dx = 2e-4;
  const GriddedCloud g = wr::grid_point_cloud(sample(f, 20000, L), opt, "test");
  ASSERT_EQ(g.map.nx, 101u);
  ASSERT_EQ(g.map.ny, 101u);
  EXPECT_EQ(g.dropouts, 0u);
  EXPECT_EQ(g.duplicates, 0u);
  const double bound = f.hessian_bound() * g.max_edge_used * g.max_edge_used / 6;
  EXPECT_LT(bound, 0.1 * f.A) << "a vacuous bound tests nothing";
  double worst = 0, sum2 = 0;
  for (std::size_t j = 0; j < g.map.ny; ++j)
    for (std::size_t i = 0; i < g.map.nx; ++i) {
      const double e = std::abs(g.map(i, j) - f(g.x0 + double(i) * opt.dx, g.y0 + double(j) * opt.dx));
      worst = std::max(worst, e);
      sum2 += e * e;
    }
  EXPECT_LE(worst, bound * (1 + 1e-9) + 1e-18);
  // And the interpolant is doing its work: its rms error is a small share of the amplitude.
  EXPECT_LT(std::sqrt(sum2 / double(g.map.size())), 0.01 * f.A);
  // Refining the cloud four times shrinks the worst error about four times (h^2 convergence).
  const GriddedCloud fine = wr::grid_point_cloud(sample(f, 80000, L), opt, "test");
  double worst_fine = 0;
  for (std::size_t j = 0; j < fine.map.ny; ++j)
    for (std::size_t i = 0; i < fine.map.nx; ++i)
      worst_fine = std::max(worst_fine, std::abs(fine.map(i, j) - f(fine.x0 + double(i) * opt.dx, fine.y0 + double(j) * opt.dx)));
  EXPECT_LT(worst_fine, 0.5 * worst);
  std::printf("[ measured ] worst error %.3g m, bound M D^2/6 %.3g m (D %.3g m, %zu points); 4x points: %.3g m\n", worst,
              bound, g.max_edge_used, g.points, worst_fine);
}

// Bar 2: a hole wider than max_gap stays a hole. A node at distance d from the hole's centre can
// only be interpolated from a triangle whose corners lie outside the hole (distance >= r) and
// whose edges are at most g; such a triangle keeps every inner point within g / sqrt 3 of a
// corner, so d >= r - g / sqrt 3. Nodes nearer the centre must be dropouts; nodes well outside
// the hole (d > r + g) sit among dense points and must not be.
TEST(PointCloud, HoleBecomesDropouts) {
  const Wave f;
  const double L = 0.02, r = 3e-3;
  PointCloudGridOptions opt;
  opt.dx = 2e-4;
  opt.max_gap = 1e-3;  // about 7 mean spacings of 20000 points on 2 cm
  const GriddedCloud g = wr::grid_point_cloud(sample(f, 20000, L, r), opt, "test");
  std::size_t inside = 0, outside = 0, must = 0;
  for (std::size_t j = 0; j < g.map.ny; ++j)
    for (std::size_t i = 0; i < g.map.nx; ++i) {
      const double d = std::hypot(g.x0 + double(i) * opt.dx - L / 2, g.y0 + double(j) * opt.dx - L / 2);
      const bool hole = std::isnan(g.map(i, j));
      if (d < r - *opt.max_gap / std::sqrt(3.0)) {
        ++must;
        inside += hole;
      }
      if (d > r + *opt.max_gap) outside += hole;
    }
  EXPECT_GT(must, 300u);
  EXPECT_EQ(inside, must);
  EXPECT_EQ(outside, 0u);
  EXPECT_GE(g.dropouts, must);
  EXPECT_LE(g.max_edge_used, *opt.max_gap);
  // Through the loader the hole's nodes are dropouts (counted, then filled) like any instrument's.
}

// A node that falls on a data point takes that point's height, on the hull's corners too (where
// the triangulation's face at the vertex can be an infinite one).
TEST(PointCloud, NodesOnDataPointsTakeTheirHeights) {
  PointCloudGridOptions opt;
  opt.dx = 0.25;
  const std::vector<CloudPoint> pts = {{0, 0, 1}, {1, 0, 2}, {0, 1, 3}, {1, 1, 4}, {0.5, 0.5, 10}, {0.3, 0.7, 5}};
  const GriddedCloud g = wr::grid_point_cloud(pts, opt, "test");
  ASSERT_EQ(g.map.nx, 5u);
  EXPECT_EQ(g.map(0, 0), 1);
  EXPECT_EQ(g.map(4, 0), 2);
  EXPECT_EQ(g.map(0, 4), 3);
  EXPECT_EQ(g.map(4, 4), 4);
  EXPECT_EQ(g.map(2, 2), 10);
  EXPECT_EQ(g.dropouts, 0u);
}

TEST(PointCloud, RefusesWhatIsNoSurface) {
  PointCloudGridOptions opt;
  opt.dx = 1e-3;
  EXPECT_THROW(wr::grid_point_cloud({{0, 0, 0}, {1, 1, 0}}, opt, "f"), wr::InputError);
  EXPECT_THROW(wr::grid_point_cloud({{0, 0, 0}, {0.01, 0.01, 0}, {0.02, 0.02, 1}}, opt, "f"), wr::InputError);  // a line
  EXPECT_THROW(wr::grid_point_cloud({{0, 0, 0}, {0.01, 0, 0}, {0, 0.01, NAN}}, opt, "f"), wr::InputError);
  opt.dx = 0;
  EXPECT_THROW(wr::grid_point_cloud({{0, 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}}, opt, "f"), wr::InputError);
  opt.dx = 1e-3;  // 22 km of cloud on a 1 mm grid: 2e7 nodes for 4 points (a unit left out)
  EXPECT_THROW(wr::grid_point_cloud({{0, 0, 0}, {0.01, 0, 0}, {0, 22e3, 0}, {0.01, 22e3, 0}}, opt, "f"), wr::InputError);
  EXPECT_THROW(wr::grid_point_cloud({{0, 0, 0}, {1e98, 0, 0}, {0, 1, 0}}, opt, "f"), wr::InputError);  // found by the fuzzer
}

// Class 4 of issue 54: the first line was dropped as a header whenever it failed to parse (a BOM
// before the first number, a typo), losing a point without a word. Now a header is only a line of
// column names; anything else unreadable is refused with its line and column.
class PointCloudText : public wr_test::ScratchTest {
 protected:
  PointCloudText() : ScratchTest("wetroad-cloud-") {}
  std::string file(const std::string& bytes) const {
    std::ofstream(path("c.xyz"), std::ios::binary) << bytes;
    return path("c.xyz");
  }
  std::string refusal(const std::string& bytes) const {
    try {
      wr::read_point_cloud_text(file(bytes), 1.0);
    } catch (const wr::InputError& e) {
      return e.what();
    }
    return "(read without an error)";
  }
};

TEST_F(PointCloudText, ByteOrderMarkIsSkippedNotTakenForAHeader) {
  const std::vector<CloudPoint> p = wr::read_point_cloud_text(file("\xEF\xBB\xBF" "0.5 0 0\n1 0 0\n0 1 1\n"), 1.0);
  ASSERT_EQ(p.size(), 3u);  // was 2: the first point went as a "header"
  EXPECT_EQ(p[0].x, 0.5);
  const std::vector<CloudPoint> h = wr::read_point_cloud_text(file("\xEF\xBB\xBF" "x,y,z\r\n0 0 0\r\n1 0 0\r\n0 1 1\r\n"), 1.0);
  EXPECT_EQ(h.size(), 3u);
}

TEST_F(PointCloudText, AFirstLineThatIsNeitherNumbersNorNamesIsRefused) {
  std::string e = refusal("1.0 2.O 3\n1 0 0\n0 1 1\n2 2 2\n");
  EXPECT_NE(e.find("line 1, column 5 (field 2): '2.O' is not a number"), std::string::npos) << e;
  EXPECT_NE(e.find("column names only"), std::string::npos) << e;
  e = refusal("x y 3\n0 0 0\n1 0 0\n0 1 1\n");  // a number among the names
  EXPECT_NE(e.find("line 1, column 1 (field 1): 'x'"), std::string::npos) << e;
  e = refusal("points: 3\n0 0 0\n1 0 0\n0 1 1\n");
  EXPECT_NE(e.find("line 1"), std::string::npos) << e;
  e = refusal("\xFF\xFE" "0 0 0\n1 0 0\n0 1 1\n");  // UTF-16's BOM: not a name either
  EXPECT_NE(e.find("line 1, column 1 (field 1)"), std::string::npos) << e;
  e = refusal("x y z\nX Y Z\n0 0 0\n");  // only the first line may be names
  EXPECT_NE(e.find("line 2, column 1 (field 1): 'X' is not a number"), std::string::npos) << e;
  e = refusal("0 0 0\n ;, \n1 0 0\n0 1 1\n");  // found by fuzz_point_cloud: index -1 of no fields
  EXPECT_NE(e.find("line 2, column 1: separators but no value"), std::string::npos) << e;
  e = refusal("0 0 0\n1 0\n");
  EXPECT_NE(e.find("line 2, column 3 (field 2): the line ends after 2 values"), std::string::npos) << e;
}

TEST_F(PointCloudText, HeadersOfColumnNamesAreSkipped) {
  for (const std::string& head : {"x y z", "X(mm);Y(mm);Z(mm);intensity", "//X,Y,Z,R,G,B", "x_m\ty_m\theight[m]",
                                  "x y z_\xC2\xB5m"}) {
    const std::vector<CloudPoint> p = wr::read_point_cloud_text(file(head + std::string("\n0 0 0\n1 0 0\n0 1 1\n")), 1.0);
    EXPECT_EQ(p.size(), 3u) << head;
  }
}

TEST_F(PointCloudText, OldMacLineEndsAreLineEnds) {
  // CR only: one line before, whose 9 values were read as one point (x y z, the rest ignored).
  const std::vector<CloudPoint> p = wr::read_point_cloud_text(file("0 0 0\r1 0 0\r0 1 1\r"), 1.0);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2].z, 1.0);
  const char nul[] = "0 0 0\r1 0 0\r0 1 \0" "1\r";  // a NUL inside the third z
  const std::string e = refusal(std::string(nul, sizeof nul - 1));
  EXPECT_NE(e.find("line 3, column 5 (field 3): '\\x001'"), std::string::npos) << e;
}

class PointCloudCli : public wr_test::Cli {};

// The text reader (a header line, commas, extra columns, millimetres) through the CLI, which says
// how it gridded the cloud; a bad line is named.
TEST_F(PointCloudCli, ReadsScannerTextAndSaysWhatItDid) {
  const Wave f;
  {
    std::ofstream o(path("scan.csv"));
    o << "x,y,z,intensity\n";
    for (const CloudPoint& p : sample(f, 4000, 0.02)) o << p.x * 1e3 << "," << p.y * 1e3 << "," << p.z * 1e3 << ",17\n";
  }
  const std::vector<CloudPoint> pts = wr::read_point_cloud_text(path("scan.csv"), 1e-3);
  ASSERT_EQ(pts.size(), 4000u);
  EXPECT_NEAR(pts[3].x, 0.02, 1e-12);
  const wr_test::CliRun r = run("analyze " + path("scan.csv") + " --points --unit mm --dx 4e-4");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("points: 51 x 51 map"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("CGAL 2-D Delaunay"), std::string::npos) << r.out;
  std::ofstream(path("bad.xyz")) << "0 0 0\n1 0 0\n0 1 x\n";
  const wr_test::CliRun b = run("analyze " + path("bad.xyz") + " --points --dx 0.1");
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.err.find("line 3"), std::string::npos) << b.err;
  const wr_test::CliRun g = run("analyze " + path("scan.csv") + " --dx 4e-4 --max-gap 1e-3");
  EXPECT_EQ(g.code, 2);
  EXPECT_NE(g.err.find("--points"), std::string::npos) << g.err;
}

}  // namespace
