// X3P (ISO 25178-72) in and out: wetroad's writer against its reader (bit-identical), files built
// here by hand after the standard (main.xml text, little-endian bytes, MD5s, zipped with libzip)
// for each data type, and damaged or unsupported archives refused in one line.
#include <gtest/gtest.h>
#include <zip.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "lib/core/content_hash.hpp"
#include "lib/core/errors.hpp"
#include "roads/surface_import.hpp"
#include "roads/x3p_file.hpp"
#include "tests/cli_fixture.hpp"

namespace {

using wr::HeightMap;
using wr_test::Cli;
using wr_test::CliRun;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A zip of the given entries (name -> bytes; a name ending in '/' a directory), deflated, as any
// archiver would make it.
void make_zip(const std::string& path, const std::map<std::string, std::string>& entries) {
  int err = 0;
  zip_t* za = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(za, nullptr);
  for (const auto& [name, bytes] : entries) {
    if (name.ends_with('/')) {  // a directory entry
      ASSERT_GE(zip_dir_add(za, name.c_str(), 0), 0);
      continue;
    }
    zip_source_t* s = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
    ASSERT_GE(zip_file_add(za, name.c_str(), s, 0), 0);
  }
  ASSERT_EQ(zip_close(za), 0);
}

template <class T>
std::string little_endian(const std::vector<T>& v) {
  std::string out;
  for (T x : v) {
    using U = std::conditional_t<sizeof(T) == 2, std::uint16_t, std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
    const U u = std::bit_cast<U>(x);
    for (std::size_t b = 0; b < sizeof(T); ++b) out += char((u >> (8 * b)) & 0xffu);
  }
  return out;
}

struct HandMade {
  std::string feature = "SUR", type = "D", cx_inc = "2e-05", cy_inc = "3e-05", z_inc = "1", z_off = "0";
  std::string ns = "http://www.opengps.eu/2008/ISO5436_2";
  std::size_t sx = 4, sy = 3;
  std::string data;                   // bindata/data.bin (empty: a DataList instead)
  std::vector<std::string> datums;    // DataList entries
  std::string valid;                  // bindata/valid.bin (empty: none)
  bool main_checksum = true, corrupt_main_checksum = false, corrupt_data_checksum = false;

  std::string xml() const {
    std::string link;
    if (!data.empty()) {
      std::string md5 = wr::md5_hex(data);
      if (corrupt_data_checksum) md5[0] = md5[0] == '0' ? '1' : '0';
      link = "<DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData>" + md5 +
             "</MD5ChecksumPointData>";
      if (!valid.empty())
        link += "<ValidPointsLink>bindata/valid.bin</ValidPointsLink><MD5ChecksumValidPoints>" + wr::md5_hex(valid) +
                "</MD5ChecksumValidPoints>";
      link += "</DataLink>";
    } else {
      link = "<DataList>";
      for (const auto& d : datums) link += "<Datum>" + d + "</Datum>";
      link += "</DataList>";
    }
    auto axis = [](const char* n, const char* at, const std::string& t, const std::string& inc, const std::string& off) {
      return std::string("<") + n + "><AxisType>" + at + "</AxisType><DataType>" + t + "</DataType><Increment>" + inc +
             "</Increment><Offset>" + off + "</Offset></" + n + ">";
    };
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<p:ISO5436_2 xmlns:p=\"" + ns + "\">"
           "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>" + feature + "</FeatureType><Axes>" +
           axis("CX", "I", "D", cx_inc, "0") + axis("CY", "I", "D", cy_inc, "0") + axis("CZ", "A", type, z_inc, z_off) +
           "</Axes></Record1><Record2><Date>2026-12-06T00:00:00Z</Date><Instrument><Manufacturer>hand</Manufacturer>"
           "<Model>test</Model><Serial>1</Serial><Version>1</Version></Instrument><CalibrationDate>2026-12-06T00:00:00Z"
           "</CalibrationDate><ProbingSystem><Type>Software</Type><Identification>test</Identification></ProbingSystem>"
           "</Record2><Record3><MatrixDimension><SizeX>" + std::to_string(sx) + "</SizeX><SizeY>" + std::to_string(sy) +
           "</SizeY><SizeZ>1</SizeZ></MatrixDimension>" + link +
           "</Record3><Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4></p:ISO5436_2>\n";
  }

  // folder: "" (the standard's layout) or "NAME/", every entry under it, as zipping a folder
  // gives; the links inside main.xml stay relative to it.
  std::map<std::string, std::string> entries(const std::string& folder = "") const {
    const std::string x = xml();
    std::map<std::string, std::string> e{{folder + "main.xml", x}};
    std::string md5 = wr::md5_hex(x);
    if (corrupt_main_checksum) md5[5] = md5[5] == 'a' ? 'b' : 'a';
    if (main_checksum) e[folder + "md5checksum.hex"] = md5 + " *main.xml\n";
    if (!data.empty()) e[folder + "bindata/data.bin"] = data;
    if (!valid.empty()) e[folder + "bindata/valid.bin"] = valid;
    return e;
  }
  void write(const std::string& path, const std::string& folder = "") const { make_zip(path, entries(folder)); }
};

class X3p : public Cli {};

HeightMap random_map(std::size_t nx, std::size_t ny, HeightMap::Kind kind) {
  HeightMap m(nx, ny, 1.25e-5, kind == HeightMap::Kind::profile ? 1.25e-5 : 2.0e-5 / 3.0, kind);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0, 3e-4);
  for (double& v : m.h) v = n(rng);
  return m;
}

// Bar 1: wetroad writes, wetroad reads: every height bit-identical, spacings exact, and the
// periodicity (wetroad.json) and dropouts kept.
TEST_F(X3p, RoundTripIsBitIdentical) {
  for (const auto kind : {HeightMap::Kind::map, HeightMap::Kind::profile}) {
    HeightMap m = random_map(kind == HeightMap::Kind::map ? 37 : 101, kind == HeightMap::Kind::map ? 23 : 1, kind);
    m.periodic = kind == HeightMap::Kind::map;
    m.h[5] = kNaN;
    wr::write_x3p(path("rt.x3p"), m, "test", {{"command", "test"}});
    const wr::X3pContents r = wr::read_x3p(path("rt.x3p"));
    EXPECT_EQ(r.feature_type, kind == HeightMap::Kind::map ? "SUR" : "PRF");
    EXPECT_EQ(r.map.kind, m.kind);
    EXPECT_EQ(r.map.nx, m.nx);
    EXPECT_EQ(r.map.ny, m.ny);
    EXPECT_EQ(r.map.dx, m.dx);
    EXPECT_EQ(r.map.dy, m.dy);
    EXPECT_EQ(r.map.periodic, m.periodic);
    EXPECT_TRUE(r.checksums_verified);
    EXPECT_EQ(r.invalid, 1u);
    for (std::size_t i = 0; i < m.h.size(); ++i)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(r.map.h[i]), std::bit_cast<std::uint64_t>(m.h[i])) << i;
  }
}

// Bar 1: hand-built maps of each data type; z = Offset + Increment x raw; invalid points by NaN
// (F, D) or by a 0 bit of valid.bin (I, L; least significant bit first).
TEST_F(X3p, HandBuiltFilesOfEveryDataType) {
  const std::vector<double> raw = {1, -2, 3, -4, 5, 60, -700, 8000, 9, -10, 11, 12};
  const std::size_t invalid_at = 6;
  for (const std::string type : {"I", "L", "F", "D"}) {
    HandMade f;
    f.type = type;
    f.z_inc = type == "F" ? "0.5" : "1.5e-06";
    f.z_off = "-2e-05";
    const double inc = std::stod(f.z_inc), off = -2e-05;
    if (type == "I") f.data = little_endian(std::vector<std::int16_t>(raw.begin(), raw.end()));
    if (type == "L") f.data = little_endian(std::vector<std::int32_t>(raw.begin(), raw.end()));
    if (type == "F" || type == "D") {
      std::vector<double> v = raw;
      v[invalid_at] = kNaN;
      f.data = type == "F" ? little_endian(std::vector<float>(v.begin(), v.end())) : little_endian(v);
    } else {
      f.valid = std::string("\xbf\x0f", 2);  // points 0-11 valid but point 6 (bit 6 of byte 0)
    }
    f.write(path("h.x3p"));
    const wr::X3pContents r = wr::read_x3p(path("h.x3p"));
    EXPECT_EQ(r.data_type, type[0]);
    EXPECT_EQ(r.map.nx, 4u);
    EXPECT_EQ(r.map.ny, 3u);
    EXPECT_EQ(r.map.dx, 2e-05);
    EXPECT_EQ(r.map.dy, 3e-05);
    EXPECT_FALSE(r.map.periodic);
    EXPECT_EQ(r.invalid, 1u) << type;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (i == invalid_at)
        EXPECT_TRUE(std::isnan(r.map.h[i])) << type;
      else
        EXPECT_EQ(r.map.h[i], off + inc * raw[i]) << type << " point " << i;
    }
  }
}

// Bar 1: a profile, with its heights inline (DataList) and an empty Datum as an invalid point.
TEST_F(X3p, HandBuiltProfileWithInlineData) {
  HandMade f;
  f.feature = "PRF";
  f.sx = 9;
  f.sy = 1;
  f.cy_inc = "0";  // a profile's CY increment is not a spacing
  f.datums = {"1e-4", "2e-4", "", "-1e-4", "0", "3e-4", "1e-4", "-2e-4", "5e-5"};
  f.write(path("p.x3p"));
  const wr::X3pContents r = wr::read_x3p(path("p.x3p"));
  EXPECT_TRUE(r.map.is_profile());
  EXPECT_EQ(r.map.nx, 9u);
  EXPECT_EQ(r.map.dx, 2e-05);
  EXPECT_EQ(r.invalid, 1u);
  EXPECT_TRUE(std::isnan(r.map.h[2]));
  EXPECT_EQ(r.map.h[5], 3e-4);
  // Through the loader: the invalid point is a dropout, filled by linear interpolation.
  const wr::LoadedSurface s = wr::load_surface(path("p.x3p"));
  EXPECT_EQ(s.format, "x3p");
  EXPECT_EQ(s.dropouts, 1u);
  EXPECT_NE(wr::describe_import(s).find("X3P PRF, data type D"), std::string::npos) << wr::describe_import(s);
}

HandMade valid_map() {
  HandMade f;
  f.data = little_endian(std::vector<double>{1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4, 7e-4, 8e-4, 9e-4, 1e-3, 1.1e-3, 1.2e-3});
  return f;
}

// Bar 1: damaged and unsupported archives: one line naming the file, exit 2, no output.
TEST_F(X3p, BadArchivesAreRefusedInOneLine) {
  HandMade ok = valid_map();
  ok.write(path("good.x3p"));
  {  // a byte of the deflated data flipped: the archive's CRC (or inflate) catches it
    std::string bytes = slurp(path("good.x3p"));
    const std::size_t at = bytes.find("bindata/data.bin") + 40;
    bytes[at] = char(bytes[at] ^ 0x5a);
    std::ofstream(path("corrupt.x3p"), std::ios::binary) << bytes;
    expect_bad_input(path("corrupt.x3p"), "damaged X3P archive");
  }
  {  // cut short: the central directory is gone
    const std::string bytes = slurp(path("good.x3p"));
    std::ofstream(path("short.x3p"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    expect_bad_input(path("short.x3p"), "not a readable X3P archive");
  }
  make_zip(path("nomain.x3p"), {{"bindata/data.bin", ok.data}});
  expect_bad_input(path("nomain.x3p"), "no main.xml");
  const struct {
    const char* file;
    std::function<void(HandMade&)> spoil;
    const char* says;
  } cases[] = {
      {"sum.x3p", [](HandMade& f) { f.corrupt_main_checksum = true; }, "checksum mismatch"},
      {"datasum.x3p", [](HandMade& f) { f.corrupt_data_checksum = true; }, "bindata/data.bin checksum mismatch"},
      {"pcl.x3p", [](HandMade& f) { f.feature = "PCL"; }, "feature type PCL"},
      {"size.x3p", [](HandMade& f) { f.sx = 5; }, "need 120"},  // 12 points held, 15 declared
      {"type.x3p", [](HandMade& f) { f.type = "Q"; }, "data type 'Q'"},
      // issue 54: ISO5436_2 in a foreign namespace is another format
      {"ns.x3p", [](HandMade& f) { f.ns = "http://example.com/not-iso"; }, "not ISO 5436-2's"},
  };
  for (const auto& c : cases) {
    HandMade bad = valid_map();
    c.spoil(bad);
    bad.write(path(c.file));
    expect_bad_input(path(c.file), c.says);
  }
}

// Issue 54 class 14a: zipping a folder puts main.xml under it (FOLDER/main.xml, with directory
// entries); such an archive reads exactly as the standard's flat layout, its links and checksum
// file taken relative to main.xml's folder. Two main.xml are refused by name.
TEST_F(X3p, MainXmlUnderATopFolder) {
  HandMade f = valid_map();
  f.valid = std::string("\xdf\x0f", 2);  // point 5 invalid: the valid-points link is followed too
  f.write(path("flat.x3p"));
  {
    std::map<std::string, std::string> e = f.entries("scan 7/");
    e["scan 7/"] = "";  // the directory entries an archiver writes (zero-length names ending in '/')
    e["scan 7/bindata/"] = "";
    make_zip(path("folder.x3p"), e);
  }
  const wr::X3pContents a = wr::read_x3p(path("flat.x3p")), b = wr::read_x3p(path("folder.x3p"));
  EXPECT_TRUE(b.checksums_verified);
  EXPECT_TRUE(b.warnings.empty());
  EXPECT_EQ(b.invalid, 1u);
  EXPECT_TRUE(std::isnan(b.map.h[5]));
  ASSERT_EQ(a.map.h.size(), b.map.h.size());
  for (std::size_t i = 0; i < a.map.h.size(); ++i)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.map.h[i]), std::bit_cast<std::uint64_t>(b.map.h[i])) << i;
  EXPECT_EQ(b.map.dx, a.map.dx);
  EXPECT_EQ(b.map.dy, a.map.dy);
  const CliRun r = run("analyze " + path("folder.x3p"));
  EXPECT_EQ(r.code, 0) << r.err;

  // A damaged file under the folder is named with its folder.
  HandMade spoilt = f;
  spoilt.corrupt_data_checksum = true;
  make_zip(path("folder-sum.x3p"), spoilt.entries("scan 7/"));
  expect_bad_input(path("folder-sum.x3p"), "scan 7/main.xml: bindata/data.bin checksum mismatch");
  // The data file sits at the root, not beside main.xml: not looked for elsewhere.
  {
    std::map<std::string, std::string> e = f.entries("scan 7/");
    e["bindata/data.bin"] = e["scan 7/bindata/data.bin"];
    e.erase("scan 7/bindata/data.bin");
    make_zip(path("folder-misplaced.x3p"), e);
  }
  expect_bad_input(path("folder-misplaced.x3p"), "no scan 7/bindata/data.bin");
  // Two measurements in one archive: which to read is not guessed.
  for (const auto& [file, second] : {std::pair<const char*, std::string>{"two-folders.x3p", "other/"},
                                     std::pair<const char*, std::string>{"root-and-folder.x3p", ""}}) {
    std::map<std::string, std::string> e = f.entries("scan 7/"), more = f.entries(second);
    e.insert(more.begin(), more.end());
    make_zip(path(file), e);
    expect_bad_input(path(file), "holds 2 main.xml files");
  }
  // Deeper than one folder is not what zipping a folder gives: still "no main.xml".
  make_zip(path("deep.x3p"), f.entries("a/b/"));
  expect_bad_input(path("deep.x3p"), "no main.xml");
}

// Without a checksum file the data are read, with a warning that main.xml was not verified.
TEST_F(X3p, MissingChecksumFileWarns) {
  HandMade f = valid_map();
  f.main_checksum = false;
  f.write(path("nosum.x3p"));
  const CliRun r = run("analyze " + path("nosum.x3p"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("not verified"), std::string::npos) << r.err;
}

// synth and fill write X3P by extension; other commands read it: the same analysis as from HDF5,
// the same wet surface as the water file's /height.
TEST_F(X3p, SynthAndFillWriteX3p) {
  ASSERT_EQ(run("synth --size 64 --dx 1e-4 --h0 2e-4 --seed 3 -q -o " + path("s.h5")).code, 0);
  ASSERT_EQ(run("synth --size 64 --dx 1e-4 --h0 2e-4 --seed 3 -q -o " + path("s.X3P")).code, 0);
  ASSERT_EQ(run("synth --size 64 --dx 1e-4 --h0 2e-4 --seed 3 -q --format x3p -o " + path("s.bin")).code, 0);
  const wr::LoadedSurface a = wr::load_surface(path("s.h5")), b = wr::load_surface(path("s.X3P")),
                          c = wr::load_surface(path("s.bin"));
  EXPECT_TRUE(b.map.periodic);
  EXPECT_EQ(b.format, "x3p");
  EXPECT_EQ(c.format, "x3p");
  for (std::size_t i = 0; i < a.map.h.size(); ++i) ASSERT_EQ(a.map.h[i], b.map.h[i]) << i;
  ASSERT_EQ(run("fill " + path("s.h5") + " --coverage 0.3 -q -o " + path("w.h5")).code, 0);
  ASSERT_EQ(run("fill " + path("s.X3P") + " --coverage 0.3 -q -o " + path("w.x3p")).code, 0);
  const wr::LoadedSurface wh = wr::load_surface(path("w.h5"), {}, wr::Levels::keep),
                          wx = wr::load_surface(path("w.x3p"), {}, wr::Levels::keep);
  for (std::size_t i = 0; i < wh.map.h.size(); ++i) ASSERT_EQ(wh.map.h[i], wx.map.h[i]) << i;
  const CliRun wet = run("friction " + path("s.h5") + " --wet " + path("w.x3p") + " -q");
  EXPECT_EQ(wet.code, 2);
  EXPECT_NE(wet.err.find("wet surface only"), std::string::npos) << wet.err;
  const CliRun said = run("fill " + path("s.X3P") + " --limit -o " + path("l.x3p"));
  EXPECT_NE(said.out.find("x3p: 64 x 64 map"), std::string::npos) << said.out;
  const CliRun bad = run("synth --size 64 -q --format tiff -o " + path("t.tif"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--format"), std::string::npos) << bad.err;
}

}  // namespace
