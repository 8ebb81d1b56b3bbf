#include "roads/surface_import.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "lib/core/errors.hpp"
#include "lib/core/least_squares.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/io/hdf5_file.hpp"
#include "roads/point_cloud_grid.hpp"
#include "roads/text_records.hpp"
#include "roads/x3p_file.hpp"

namespace wr {
namespace {

// Working copies the analysis holds besides the map (FFT buffers, sorted copies, profiles).
constexpr double kAnalysisCopies = 6.0;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// Sample spacings of road texture lie far inside 1 nm ... 1 m; outside, a unit was given wrong,
// and every cost that scales with extent / spacing (the FEM's mesh, the MPD's resampling) would
// run away before any check of its own: refused here, where every surface passes.
constexpr double kMinSpacing = 1e-9, kMaxSpacing = 1.0;

void check_spacing(double d, const std::string& name, const std::string& source) {
  if (!std::isfinite(d) || !(d > 0)) throw InputError(source, name + " must be a positive spacing in m (got " + num(d) + ")");
  if (d < kMinSpacing || d > kMaxSpacing)
    throw InputError(source, name + " = " + num(d) + " m is outside 1e-09 ... 1 m, the sample spacings of road texture "
                                                    "(a unit given wrong?)");
}

void check_size(const HeightMap& m, const std::string& source) {
  if (m.is_profile()) {
    if (m.nx < 8) throw InputError(source, "a profile needs at least 8 samples (got " + std::to_string(m.nx) + ")");
  } else if (m.nx < 2 || m.ny < 2) {
    throw InputError(source, "a " + std::to_string(m.ny) + "x" + std::to_string(m.nx) +
                                 " map has no texture to analyze; a map needs at least 2x2 samples");
  }
}

std::optional<SynthesisRecord> read_synthesis(const Hdf5Reader& f) {
  if (!f.has_group("/synthesis")) return std::nullopt;
  auto get = [&](const char* name) {
    auto v = f.attr_double("/synthesis", name);
    if (!v) throw InputError(f.path(), std::string("/synthesis lacks attribute ") + name);
    if (!std::isfinite(*v)) throw InputError(f.path(), std::string("/synthesis attribute ") + name + " is not finite");
    return *v;
  };
  // A whole number in [lo, hi] (a cast of anything else is undefined behaviour).
  auto whole = [&](const char* name, double lo, double hi) {
    const double v = get(name);
    if (!(v >= lo && v <= hi && v == std::floor(v)))
      throw InputError(f.path(), std::string("/synthesis attribute ") + name + " is not a whole number in " + num(lo) +
                                     " ... " + num(hi));
    return v;
  };
  SynthesisRecord s;
  s.psd.h0 = get("h0");
  s.psd.hurst = get("hurst");
  s.psd.qL = get("qL");
  s.psd.q0 = get("q0");
  s.psd.q1 = get("q1");
  s.psd.q1_cut = get("q1_cut");
  s.psd.k = get("plateau_k");
  s.k_eq44 = get("plateau_k_eq44");
  s.h0_eq44_on_lattice = get("h0_eq44_on_lattice");
  s.seed = static_cast<std::uint64_t>(whole("seed", 0, double(kMaxSeed)));
  s.oversample = static_cast<int>(whole("oversample", 1, 64));
  // Files written before the sampling was recorded are band-limited.
  s.sampling = sampling_from_name(f.attr_string("/synthesis", "sampling").value_or("nyquist")).value_or(Sampling::nyquist);
  return s;
}

LoadedSurface load_hdf5(const std::string& path) {
  Hdf5Reader f(path);
  LoadedSurface out;
  out.source = path;
  out.format = "hdf5";
  std::string ds;
  if (f.has_dataset("/height"))
    ds = "/height";
  else if (f.has_dataset("/profile"))
    ds = "/profile";
  else
    throw InputError(path, "no /height (2-D map) or /profile (1-D line) dataset");
  const auto dims = f.dims(ds);
  const bool profile = ds == "/profile";
  if (!profile && dims.size() != 2)
    throw InputError(path, "/height must be 2-D (rows = y), got rank " + std::to_string(dims.size()) +
                               (dims.size() == 1 ? " (a 1-D line belongs in /profile)" : ""));
  if (profile && dims.size() != 1)
    throw InputError(path, "/profile must be 1-D, got rank " + std::to_string(dims.size()));
  const auto dx = f.attr_double(ds, "dx");
  if (!dx) throw InputError(path, ds + " has no dx attribute (sample spacing in m)");
  check_spacing(*dx, "dx", path);
  double dy = *dx;
  if (!profile) {
    if (auto v = f.attr_double(ds, "dy")) dy = *v;
    check_spacing(dy, "dy", path);
  }
  const std::size_t ny = profile ? 1 : dims[0];
  const std::size_t nx = profile ? dims[0] : dims[1];
  const std::size_t cells = checked_cells(nx, ny, path);
  require_memory(cells, sizeof(double), kAnalysisCopies, path,
                 "analyzing a " + std::to_string(ny) + "x" + std::to_string(nx) + " map");
  HeightMap m;
  m.nx = nx;
  m.ny = ny;
  m.dx = *dx;
  m.dy = dy;
  m.kind = profile ? HeightMap::Kind::profile : HeightMap::Kind::map;
  check_size(m, path);
  // No unit attribute: metres (design.md); one that is present must be read and known.
  const double scale = unit_scale(f.attr_string(ds, "unit").value_or("m"), path + " (" + ds + " unit)");
  const double periodic = f.attr_double(ds, "periodic").value_or(0.0);
  if (periodic != 0.0 && periodic != 1.0)
    throw InputError(path, ds + " attribute periodic is " + num(periodic) + "; it must be 0 (not periodic) or 1 (periodic)");
  m.periodic = periodic == 1.0;
  m.h.resize(cells);
  f.read_doubles(ds, m.h.data(), cells);
  if (scale != 1.0)
    for (double& v : m.h) v *= scale;
  out.map = std::move(m);
  out.unit_scale = scale;
  out.synthesis = read_synthesis(f);
  return out;
}

LoadedSurface load_text(const std::string& path, const TextGridOptions& opt) {
  if (!opt.dx) throw InputError(path, "not an HDF5 file; to read it as a plain-text grid give --dx (m)");
  check_spacing(*opt.dx, "--dx", path);
  const double dy = opt.dy.value_or(*opt.dx);
  check_spacing(dy, "--dy", path);
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open");
  const auto file_bytes = std::filesystem::file_size(path);
  require_memory(file_bytes / 2 + 1, sizeof(double), kAnalysisCopies, path, "reading this text grid");
  std::vector<double> values;
  std::size_t cols = 0, rows = 0;
  TextRecords rec(in);
  while (rec.next()) {
    const std::vector<std::string>& fields = rec.fields();
    if (fields.empty())
      throw InputError(path, "line " + std::to_string(rec.line()) + ", column 1: separators but no value (NaN marks a dropout)");
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const std::optional<double> v = parse_number(fields[k]);
      if (!v) throw InputError(path, rec.where(k) + ": '" + shown_token(fields[k]) + "' is not a number");
      values.push_back(*v);
    }
    if (rows == 0)
      cols = fields.size();
    else if (fields.size() > cols)
      throw InputError(path, rec.where(cols) + ": value " + std::to_string(cols + 1) + " of a line of " +
                                 std::to_string(fields.size()) + "; the first row has " + std::to_string(cols));
    else if (fields.size() < cols)
      throw InputError(path, rec.where(fields.size() - 1) + ": the line ends after " + std::to_string(fields.size()) +
                                 " values; the first row has " + std::to_string(cols));
    ++rows;
  }
  if (rows == 0) throw InputError(path, "no numbers found (empty file?)");
  LoadedSurface out;
  out.source = path;
  out.format = "text";
  HeightMap m;
  if (rows == 1 || cols == 1) {  // one line of samples: a profile
    m.kind = HeightMap::Kind::profile;
    m.nx = values.size();
    m.ny = 1;
    m.dx = m.dy = *opt.dx;
  } else {
    m.nx = cols;
    m.ny = rows;
    m.dx = *opt.dx;
    m.dy = dy;
  }
  m.periodic = opt.periodic;
  check_size(m, path);
  for (double& v : values) v *= opt.unit_scale;
  m.h.assign(values.begin(), values.end());
  out.map = std::move(m);
  out.unit_scale = opt.unit_scale;
  return out;
}

LoadedSurface load_x3p(const std::string& path) {
  X3pContents x = read_x3p(path);
  LoadedSurface out;
  out.source = path;
  out.format = "x3p";
  check_size(x.map, path);
  check_spacing(x.map.dx, "the x increment", path);
  if (!x.map.is_profile()) check_spacing(x.map.dy, "the y increment", path);
  out.detail = "X3P " + x.feature_type + ", data type " + std::string(1, x.data_type) +
               (x.checksums_verified ? ", checksums verified" : ", main.xml checksum absent") +
               (x.creator.empty() ? std::string() : ", written by " + x.creator);
  out.warnings = std::move(x.warnings);
  out.map = std::move(x.map);
  return out;
}

LoadedSurface load_points(const std::string& path, const TextGridOptions& opt) {
  if (!opt.dx) throw InputError(path, "a point cloud needs --dx (m), the spacing of the grid to interpolate onto");
  check_spacing(*opt.dx, "--dx", path);
  if (opt.dy) check_spacing(*opt.dy, "--dy", path);
  PointCloudGridOptions g;
  g.dx = *opt.dx;
  g.dy = opt.dy;
  g.max_gap = opt.max_gap;
  GriddedCloud c = grid_point_cloud(read_point_cloud_text(path, opt.unit_scale), g, path);
  LoadedSurface out;
  out.source = path;
  out.format = "points";
  out.unit_scale = opt.unit_scale;
  out.detail = std::to_string(c.points) + " points (" + std::to_string(c.duplicates) + " at repeated x, y), mean spacing " +
               num(c.mean_spacing) + " m, longest triangle edge used " + num(c.max_edge_used) + " m; " + c.method;
  check_size(c.map, path);
  out.map = std::move(c.map);
  return out;
}

// The HDF5 signature stands at byte 0, or after a user block of 512, 1024, 2048, ... bytes
// (HDF5 File Format Specification, "Format Signature"): a file with a user block is HDF5 too.
bool looks_like_hdf5(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  static const char kSig[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  for (std::uint64_t offset = 0; in; offset = offset ? 2 * offset : 512) {
    char sig[8] = {};
    in.seekg(std::streamoff(offset));
    in.read(sig, 8);
    if (in.gcount() < 8) return false;
    if (std::equal(sig, sig + 8, kSig)) return true;
    if (offset >= (std::uint64_t{1} << 40)) return false;
  }
  return false;
}

}  // namespace

double unit_scale(const std::string& unit, const std::string& source) {
  // Writers differ in case and in the micro sign (U+00B5 or Greek mu U+03BC); nothing else is
  // guessed: an unknown name is refused rather than read as metres.
  const auto first = unit.find_first_not_of(" \t"), last = unit.find_last_not_of(" \t");
  std::string u = first == std::string::npos ? "" : unit.substr(first, last - first + 1);
  for (char& ch : u)
    if (ch >= 'A' && ch <= 'Z') ch = char(ch - 'A' + 'a');
  if (u == "m" || u == "meter" || u == "metre") return 1.0;
  if (u == "mm") return 1e-3;
  if (u == "um" || u == "\u00b5m" || u == "\u03bcm" || u == "micron") return 1e-6;
  if (u == "nm") return 1e-9;
  throw InputError(source, "unknown height unit '" + unit + "' (expected m, mm, um or nm)");
}

std::size_t fill_dropouts(HeightMap& m) {
  std::size_t missing = 0;
  for (double v : m.h) missing += !std::isfinite(v);
  if (missing == 0) return 0;
  if (missing == m.h.size()) return missing;  // caller reports "all dropouts"
  if (m.is_profile()) {
    std::vector<std::size_t> valid;
    for (std::size_t i = 0; i < m.nx; ++i)
      if (std::isfinite(m.h[i])) valid.push_back(i);
    std::size_t k = 0;
    for (std::size_t i = 0; i < m.nx; ++i) {
      if (std::isfinite(m.h[i])) continue;
      while (k + 1 < valid.size() && valid[k + 1] < i) ++k;
      if (i < valid.front())
        m.h[i] = m.h[valid.front()];
      else if (i > valid.back())
        m.h[i] = m.h[valid.back()];
      else {
        const std::size_t a = valid[k], b = valid[k + 1];
        const double t = double(i - a) / double(b - a);
        m.h[i] = (1 - t) * m.h[a] + t * m.h[b];
      }
    }
    return missing;
  }
  // Layer by layer, visiting only the layer's cells (the dropouts next to a filled or valid
  // cell): linear in the map's size however deep the holes (a sparse point cloud's grid is
  // mostly hole). Each layer is computed from the state before it, then written.
  const long nx = long(m.nx), ny = long(m.ny);
  auto neighbour = [&](std::size_t c, int d) -> long {  // -x, +x, -y, +y; -1 beyond an open edge
    long jx = long(c % m.nx) + (d == 0 ? -1 : d == 1 ? 1 : 0), jy = long(c / m.nx) + (d == 2 ? -1 : d == 3 ? 1 : 0);
    if (m.periodic) {
      jx = (jx + nx) % nx;
      jy = (jy + ny) % ny;
    } else if (jx < 0 || jy < 0 || jx >= nx || jy >= ny) {
      return -1;
    }
    return jy * nx + jx;
  };
  std::vector<unsigned char> queued(m.h.size(), 0);
  std::vector<std::size_t> layer, next;
  auto enqueue_dropout_neighbours = [&](std::size_t c) {
    for (int d = 0; d < 4; ++d) {
      const long k = neighbour(c, d);
      if (k >= 0 && !queued[std::size_t(k)] && !std::isfinite(m.h[std::size_t(k)])) {
        queued[std::size_t(k)] = 1;
        next.push_back(std::size_t(k));
      }
    }
  };
  for (std::size_t c = 0; c < m.h.size(); ++c)
    if (std::isfinite(m.h[c])) enqueue_dropout_neighbours(c);
  std::vector<double> value;
  std::size_t left = missing;
  while (!next.empty()) {
    layer.swap(next);
    next.clear();
    value.assign(layer.size(), 0.0);
    for (std::size_t k = 0; k < layer.size(); ++k) {
      double s = 0;
      int n = 0;
      for (int d = 0; d < 4; ++d) {
        const long j = neighbour(layer[k], d);
        if (j < 0 || !std::isfinite(m.h[std::size_t(j)])) continue;
        s += 0.25 * m.h[std::size_t(j)];  // a quarter each: the sum of four near DBL_MAX stays finite
        ++n;
      }
      value[k] = s * (4.0 / n);  // n >= 1: each cell of a layer touches a valid or filled one
    }
    for (std::size_t k = 0; k < layer.size(); ++k) m.h[layer[k]] = value[k];
    for (std::size_t c : layer) enqueue_dropout_neighbours(c);
    if (layer.size() > left) throw std::logic_error("fill_dropouts filled a cell twice");
    left -= layer.size();
  }
  if (left != 0) throw std::logic_error("fill_dropouts left a hole unreached");
  return missing;
}

MeanPlane fit_mean_plane(const HeightMap& m, const std::vector<unsigned char>& dropout) {
  // Centred coordinates decouple the offset from the slopes (sx = sy = 0 without dropouts).
  const double cx = 0.5 * (m.nx - 1), cy = 0.5 * (m.ny - 1);
  double sxx = 0, syy = 0, sxy = 0, sx = 0, sy = 0, n = 0, sz = 0, sxz = 0, syz = 0;
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix) {
      if (dropout[iy * m.nx + ix]) continue;
      const double x = (ix - cx) * m.dx, y = (iy - cy) * m.dy, z = m(ix, iy);
      n += 1;
      sx += x;
      sy += y;
      sxx += x * x;
      syy += y * y;
      sxy += x * y;
      sz += z;
      sxz += x * z;
      syz += y * z;
    }
  // Normal equations [n sx sy; sx sxx sxy; sy sxy syy] [a bx by] = [sz sxz syz].
  Eigen::Matrix3d N;
  N << n, sx, sy, sx, sxx, sxy, sy, sxy, syy;
  const Eigen::Vector3d r(sz, sxz, syz);
  // A periodic surface has no tilt (a trend would break the periodicity), and a least-squares
  // plane through one period of it would only remove genuine long-wavelength texture:
  // remove its mean level alone.
  const int dim = m.periodic ? 1 : (m.is_profile() ? 2 : 3);  // a profile has no y slope
  const Eigen::VectorXd c = solve_normal_equations(N.topLeftCorner(dim, dim), r.head(dim));
  return {c(0), dim >= 2 ? c(1) : 0.0, dim == 3 ? c(2) : 0.0};
}

MeanPlane remove_mean_plane(HeightMap& m, const std::vector<unsigned char>& dropout) {
  const MeanPlane p = fit_mean_plane(m, dropout);
  const double cx = 0.5 * (m.nx - 1), cy = 0.5 * (m.ny - 1);
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix)
      m(ix, iy) -= p.offset + p.tilt_x * (ix - cx) * m.dx + p.tilt_y * (iy - cy) * m.dy;
  return p;
}

void require_periodic_map(const LoadedSurface& s, const std::string& why) {
  if (s.map.is_profile())
    throw InputError(s.source, "a 1-D profile (/profile); " + why + ": give a 2-D height map (/height)");
  if (!s.map.periodic) throw InputError(s.source, "not a periodic surface (attribute periodic = 0); " + why);
}

namespace {

// Heights of a texture in metres: the limits beyond which the unit, not the road, is wrong.
constexpr double kWarnHeight = 0.1, kMaxHeight = 1e3;
constexpr double kWarnDropouts = 0.1;  // ISO 13473-1 rejects a segment above 10 % dropouts

std::vector<std::string> check_plausible(const LoadedSurface& s) {
  std::vector<std::string> warnings;
  const double share = double(s.dropouts) / double(s.map.h.size());
  if (share > kWarnDropouts)
    warnings.push_back(num(100 * share) + " % of the samples are dropouts, filled by interpolation: the statistics "
                       "rest on the remaining " + num(100 * (1 - share)) + " %");
  double peak = 0;
  for (double v : s.map.h) peak = std::max(peak, std::abs(v - s.kept_offset));
  if (!(peak <= kMaxHeight))
    throw InputError(s.source, "heights up to " + num(peak) + " m about the mean plane: not a road texture "
                               "(a unit other than metres? set the 'unit' attribute or --unit)");
  if (peak > kWarnHeight)
    warnings.push_back("heights up to " + num(peak) + " m about the mean plane, beyond any road texture: "
                       "check the unit");
  return warnings;
}

}  // namespace

std::string describe_import(const LoadedSurface& s) {
  const HeightMap& m = s.map;
  std::string line = s.format + ": ";
  line += m.is_profile() ? "profile of " + std::to_string(m.nx) + " samples, dx " + num(m.dx) + " m"
                         : std::to_string(m.ny) + " x " + std::to_string(m.nx) + " map (rows = y), dx " + num(m.dx) +
                               " m, dy " + num(m.dy) + " m";
  line += m.periodic ? ", periodic" : ", not periodic";
  line += s.unit_scale == 1.0 ? ", heights in m" : ", heights read in units of " + num(s.unit_scale) + " m";
  if (s.dropouts)
    line += ", " + std::to_string(s.dropouts) + " invalid (" + num(100.0 * double(s.dropouts) / double(m.h.size())) +
            " %) filled " + (m.is_profile() ? "by linear interpolation" : "from their valid neighbours");
  else
    line += ", no invalid points";
  if (!s.detail.empty()) line += "; " + s.detail;
  return line;
}

LoadedSurface load_surface(const std::string& path, const TextGridOptions& text, Levels levels) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a file");
  // A FIFO would block the open below until a writer comes (and could not be read twice).
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, "is not a regular file (a pipe, device or socket); save it to a file first");
  if (std::ifstream probe(path, std::ios::binary); !probe)
    throw InputError(path, std::string("cannot read: ") + std::strerror(errno));
  const std::string ext = std::filesystem::path(path).extension().string();
  LoadedSurface s;
  const bool hdf5 = looks_like_hdf5(path), x3p = !hdf5 && (looks_like_zip(path) || ext == ".x3p");
  if ((hdf5 || x3p) && !text.given.empty())
    throw InputError(path, text.given.front() + " applies to plain-text grids and point clouds; an " +
                               (hdf5 ? "HDF5" : "X3P") + " file carries its own spacing, units and periodicity");
  if (hdf5)
    s = load_hdf5(path);
  else if (x3p)
    s = load_x3p(path);
  else if (ext == ".h5" || ext == ".hdf5" || ext == ".he5")
    throw InputError(path, "not an HDF5 file");
  else if (!text.dx)
    throw InputError(path, "not an HDF5 or X3P file (for a plain-text grid or point cloud give --dx)");
  else if (text.points)
    s = load_points(path, text);
  else
    s = load_text(path, text);

  HeightMap& m = s.map;
  s.dropout.assign(m.h.size(), 0);
  for (std::size_t i = 0; i < m.h.size(); ++i) s.dropout[i] = !std::isfinite(m.h[i]);
  s.dropouts = static_cast<std::size_t>(std::count(s.dropout.begin(), s.dropout.end(), 1));
  if (s.dropouts == m.h.size()) throw InputError(path, "every sample is a dropout (NaN); nothing to analyze");
  fill_dropouts(m);
  const bool keep = levels == Levels::keep && m.periodic;
  const MeanPlane p = keep ? fit_mean_plane(m, s.dropout) : remove_mean_plane(m, s.dropout);
  s.offset = p.offset;
  s.kept_offset = keep ? p.offset : 0;
  s.tilt_x = p.tilt_x;
  s.tilt_y = p.tilt_y;
  for (std::string& w : check_plausible(s)) s.warnings.push_back(std::move(w));
  return s;
}

}  // namespace wr
