#include "roads/point_cloud_grid.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "lib/core/errors.hpp"
#include "lib/core/memory_guard.hpp"
#include "roads/text_records.hpp"

namespace wr {
namespace {

// Exact predicates: the orientation tests of the triangulation never err on nearly collinear
// scanner points (rows of a line scanner are exactly that); coordinates stay doubles.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<double, Kernel>;  // info: z
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using Point2 = Kernel::Point_2;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

double squared_longest_edge(const Delaunay::Face_handle& f) {
  double m = 0;
  for (int i = 0; i < 3; ++i)
    m = std::max(m, CGAL::to_double(CGAL::squared_distance(f->vertex(i)->point(), f->vertex((i + 1) % 3)->point())));
  return m;
}

// Area of the convex hull: the finite faces of a Delaunay triangulation tile it.
double hull_area(const Delaunay& dt) {
  double a = 0;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) a += std::abs(dt.triangle(f).area());
  return a;
}

// Linear interpolant on face f at p (barycentric weights from signed sub-triangle areas).
double interpolate_on(const Delaunay::Face_handle& f, const Point2& p) {
  const Point2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
  auto area2 = [](const Point2& u, const Point2& v, const Point2& w) {
    return (v.x() - u.x()) * (w.y() - u.y()) - (w.x() - u.x()) * (v.y() - u.y());
  };
  const double total = area2(a, b, c);
  const double la = area2(p, b, c) / total, lb = area2(a, p, c) / total, lc = 1.0 - la - lb;
  return la * f->vertex(0)->info() + lb * f->vertex(1)->info() + lc * f->vertex(2)->info();
}

// A header line: at least x y z, every field a name (a letter or '_' first, then letters,
// digits and unit punctuation such as z_mm, Z(um), height[m]; bytes of UTF-8 letters allowed)
// and none a number (strtod also reads "nan", "inf"). CloudCompare writes its header as "//X,Y,Z".
bool is_column_names(const std::vector<std::string>& fields) {
  if (fields.size() < 3) return false;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    std::string f = fields[k];
    if (k == 0 && f.rfind("//", 0) == 0) f.erase(0, 2);
    if (f.empty() || parse_number(f)) return false;
    const auto first = static_cast<unsigned char>(f[0]);
    if (!(std::isalpha(first) || first == '_' || first >= 0x80)) return false;
    for (const char ch : f) {
      const auto c = static_cast<unsigned char>(ch);
      if (!(std::isalnum(c) || c >= 0x80 || std::string_view("_-.()[]/%").find(ch) != std::string_view::npos)) return false;
    }
  }
  return true;
}

}  // namespace

GriddedCloud grid_point_cloud(const std::vector<CloudPoint>& points, const PointCloudGridOptions& opt,
                              const std::string& source) {
  if (!(opt.dx > 0) || !std::isfinite(opt.dx)) throw InputError(source, "--dx must be a positive grid spacing in m");
  const double dy = opt.dy.value_or(opt.dx);
  if (!(dy > 0) || !std::isfinite(dy)) throw InputError(source, "--dy must be a positive grid spacing in m");
  if (opt.max_gap && !(*opt.max_gap > 0)) throw InputError(source, "--max-gap must be a positive length in m");
  if (points.size() < 3) throw InputError(source, "a point cloud needs at least 3 points (got " + std::to_string(points.size()) + ")");
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  std::vector<std::pair<Point2, double>> sites;
  sites.reserve(points.size());
  for (const CloudPoint& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(source, "a point has a non-finite coordinate (x, y and z must be numbers)");
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    sites.emplace_back(Point2(p.x, p.y), p.z);
  }
  // Node counts in floating point first: a span of 1e98 m must not overflow the cast.
  const double fnx = std::floor((x1 - x0) / opt.dx * (1 + 1e-12)) + 1, fny = std::floor((y1 - y0) / dy * (1 + 1e-12)) + 1;
  if (fnx < 2 || fny < 2)
    throw InputError(source, "the points span " + num(x1 - x0) + " x " + num(y1 - y0) + " m: under two grid spacings");
  // A grid far finer than the cloud is all interpolation (and, at millions of nodes per point,
  // a unit or spacing given wrong): refuse it before allocating.
  if (!(fnx * fny <= kMaxNodesPerPoint * double(points.size())))
    throw InputError(source, "--dx " + num(opt.dx) + " m makes " + num(fny) + " x " + num(fnx) + " grid nodes for " +
                                 std::to_string(points.size()) + " points: give a spacing near the points' own (their extent is " +
                                 num(x1 - x0) + " x " + num(y1 - y0) + " m; check --unit)");
  const std::size_t nx = std::size_t(fnx), ny = std::size_t(fny);
  const std::size_t cells = checked_cells(nx, ny, source);
  require_memory(cells, sizeof(double), 6.0, source, "gridding this point cloud");

  // Spatially sorted insertion (CGAL's range constructor) keeps the walk short; of points at a
  // repeated (x, y) one keeps its z.
  const Delaunay dt(sites.begin(), sites.end());
  if (dt.dimension() < 2) throw InputError(source, "the points lie on one line in x, y: no surface to grid");

  GriddedCloud out;
  out.points = points.size();
  out.duplicates = points.size() - dt.number_of_vertices();
  out.mean_spacing = std::sqrt(hull_area(dt) / double(dt.number_of_vertices()));
  out.max_gap = opt.max_gap.value_or(kDefaultGapSpacings * out.mean_spacing);
  out.x0 = x0;
  out.y0 = y0;
  out.map = HeightMap(nx, ny, opt.dx, dy);
  out.map.periodic = false;
  const double gap2 = out.max_gap * out.max_gap;
  double used2 = 0;
  Delaunay::Face_handle hint;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      // Row order: each node starts its walk from the previous node's face (a step away).
      const std::size_t ii = (j % 2 == 0) ? i : nx - 1 - i;
      const Point2 p(x0 + double(ii) * opt.dx, y0 + double(j) * dy);
      Delaunay::Locate_type lt;
      int li = 0;
      Delaunay::Face_handle f = dt.locate(p, lt, li, hint);
      double& h = out.map(ii, j);
      h = std::numeric_limits<double>::quiet_NaN();
      if (lt == Delaunay::OUTSIDE_CONVEX_HULL || lt == Delaunay::OUTSIDE_AFFINE_HULL) continue;
      if (lt == Delaunay::VERTEX) {  // the node is a data point: its own height
        h = f->vertex(li)->info();
        continue;
      }
      if (dt.is_infinite(f)) f = f->neighbor(li);  // on a hull edge: the finite face across it
      hint = f;
      const double e2 = squared_longest_edge(f);
      if (e2 > gap2) continue;
      used2 = std::max(used2, e2);
      h = interpolate_on(f, p);
    }
  out.max_edge_used = std::sqrt(used2);
  out.dropouts = std::size_t(std::count_if(out.map.h.begin(), out.map.h.end(), [](double v) { return std::isnan(v); }));
  out.method = "point cloud: linear interpolation on the CGAL 2-D Delaunay triangulation of " +
               std::to_string(dt.number_of_vertices()) + " points, triangles with an edge over " + num(out.max_gap) +
               " m left as dropouts";
  return out;
}

std::vector<CloudPoint> read_point_cloud_text(const std::string& path, double unit_scale) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open");
  std::vector<CloudPoint> pts;
  std::size_t records = 0;
  TextRecords rec(in);
  while (rec.next()) {
    const std::vector<std::string>& fields = rec.fields();
    if (fields.empty())
      throw InputError(path, "line " + std::to_string(rec.line()) + ", column 1: separators but no value (a point is x y z)");
    if (++records == 1 && is_column_names(fields)) continue;
    if (fields.size() < 3)
      throw InputError(path, rec.where(fields.size() - 1) + ": the line ends after " + std::to_string(fields.size()) +
                                 " values; a point cloud needs x y z on every line");
    double v[3];
    for (std::size_t n = 0; n < 3; ++n) {
      const std::optional<double> x = parse_number(fields[n]);
      // A first line that is neither numbers nor names (a typo such as 2.O, a stray byte) is
      // refused like any other: skipping it as a header would lose a point without a word.
      if (!x)
        throw InputError(path, rec.where(n) + ": '" + shown_token(fields[n]) + "' is not a number" +
                                   (records == 1 ? " (a header line must hold column names only, such as x y z)" : ""));
      v[n] = *x;
    }
    pts.push_back({v[0] * unit_scale, v[1] * unit_scale, v[2] * unit_scale});
  }
  if (pts.empty()) throw InputError(path, "no points found (empty file?)");
  return pts;
}

}  // namespace wr
