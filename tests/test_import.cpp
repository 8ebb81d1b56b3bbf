// Import: text grids, HDF5 round trip, dropout filling, mean-plane removal.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <hdf5.h>

#include "lib/core/errors.hpp"
#include "roads/surface_file.hpp"
#include "roads/surface_import.hpp"

namespace wr {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("wetroad-test-" + std::to_string(::getpid()) + "-" + name)).string();
}

TEST(Import, TextGridWithCommasAndDropout) {
  const std::string path = temp_path("grid.csv");
  {
    std::ofstream f(path);
    f << "# a 3 x 4 grid in mm\n1,2,3,4\n5,NaN,7,8\n9,10,11,12\n";
  }
  TextGridOptions opt;
  opt.dx = 1e-4;
  opt.unit_scale = 1e-3;
  const LoadedSurface s = load_surface(path, opt);
  std::filesystem::remove(path);
  EXPECT_EQ(s.map.nx, 4u);
  EXPECT_EQ(s.map.ny, 3u);
  EXPECT_EQ(s.dropouts, 1u);
  EXPECT_EQ(s.format, "text");
  // Heights h = (1 + ix + 4 iy) mm form an exact plane: after removal everything is zero,
  // including the filled dropout (mean of 2, 5, 7, 10 = 6 mm, on the plane).
  for (double v : s.map.h) EXPECT_NEAR(v, 0.0, 1e-15);
  EXPECT_NEAR(s.tilt_x, 1e-3 / 1e-4, 1e-9);
  EXPECT_NEAR(s.tilt_y, 4e-3 / 1e-4, 1e-9);
  EXPECT_NEAR(s.offset, 6.5e-3, 1e-15);
}

TEST(Import, RaggedTextIsRefusedNamingTheLine) {
  const std::string path = temp_path("ragged.txt");
  {
    std::ofstream f(path);
    f << "1 2 3\n4 5\n";
  }
  TextGridOptions opt;
  opt.dx = 1e-4;
  try {
    load_surface(path, opt);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

// Class 4 of issue 54: a text reader reads exactly what is there or refuses naming the line and
// column. Each case below was read wrong with exit 0 before.
std::string write_bytes(const std::string& name, const std::string& bytes) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string refusal(const std::string& path, const TextGridOptions& opt) {
  try {
    load_surface(path, opt);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read without an error)";
}

TEST(Import, NulByteInsideANumberIsRefusedNamingLineAndColumn) {
  // "4\0" "5": strtod on c_str() read 4 and dropped the rest of the token.
  const std::string path = write_bytes("nul.txt", std::string("1 2\n3 4\0" "5\n", 11));
  TextGridOptions opt;
  opt.dx = 1e-4;
  const std::string e = refusal(path, opt);
  std::filesystem::remove(path);
  EXPECT_NE(e.find("line 2, column 3 (field 2)"), std::string::npos) << e;
  EXPECT_NE(e.find("'4\\x005' is not a number"), std::string::npos) << e;  // the NUL shown, on one line
}

// Issue 54 class 2: a FIFO (a path that is no regular file) is refused before it is opened; an
// open would block until a writer came, a hang rather than an answer.
TEST(Import, AFifoIsRefusedNotOpened) {
  const std::string path = (std::filesystem::temp_directory_path() / ("wetroad-fifo-" + std::to_string(::getpid()))).string();
  ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
  TextGridOptions opt;
  opt.dx = 1e-4;
  const std::string e = refusal(path, opt);
  std::filesystem::remove(path);
  EXPECT_NE(e.find("not a regular file"), std::string::npos) << e;
}

TEST(Import, EveryLineEndCountsOnceOldMacCrIncluded) {
  TextGridOptions opt;
  opt.dx = 1e-4;
  // CR only (old Mac OS) was one line: a 1 x 9 profile. CRLF, LF and CR mixed in one file too.
  for (const std::string& text : {std::string("1 2 3\r4 5 6\r7 8 9\r"), std::string("1 2 3\r\n4 5 6\r7 8 9\n"),
                                  std::string("# mm\r\r\n1 2 3\r\n4 5 6\r\n7 8 9")}) {
    const std::string path = write_bytes("cr.txt", text);
    const LoadedSurface s = load_surface(path, opt);
    std::filesystem::remove(path);
    EXPECT_EQ(s.map.kind, HeightMap::Kind::map);
    EXPECT_EQ(s.map.nx, 3u);
    EXPECT_EQ(s.map.ny, 3u);
  }
  // Lines are counted with every end: the bad value on the fourth line (CR, CR LF, CR) is named there.
  const std::string path = write_bytes("cr-bad.txt", "1 2\r\r\n3 4\r5 x\r");
  const std::string e = refusal(path, opt);
  std::filesystem::remove(path);
  EXPECT_NE(e.find("line 4, column 3 (field 2): 'x' is not a number"), std::string::npos) << e;
}

TEST(Import, Utf8ByteOrderMarkIsSkipped) {
  // A 3 x 3 grid, 9 at the centre and 0 around it; with a BOM its first value was "\xEF\xBB\xBF0".
  const std::string path = write_bytes("bom.csv", "\xEF\xBB\xBF" "0,0,0\n0,9,0\n0,0,0\n");
  TextGridOptions opt;
  opt.dx = 1e-4;
  opt.unit_scale = 1.0;
  const LoadedSurface s = load_surface(path, opt);
  std::filesystem::remove(path);
  ASSERT_EQ(s.map.nx, 3u);
  ASSERT_EQ(s.map.ny, 3u);
  EXPECT_NEAR(s.offset, 1.0, 1e-12);  // the mean plane: no tilt, the mean 1
  EXPECT_NEAR(s.map(1, 1), 8.0, 1e-12);
  EXPECT_NEAR(s.map(0, 0), -1.0, 1e-12);
  // A BOM anywhere else is not a line end or a separator: refused where it stands.
  const std::string mid = write_bytes("bom-mid.csv", "0,0,0\n0,\xEF\xBB\xBF" "9,0\n");
  const std::string e = refusal(mid, opt);
  std::filesystem::remove(mid);
  EXPECT_NE(e.find("line 2, column 3 (field 2)"), std::string::npos) << e;
}

TEST(Import, RaggedRowsAreNamedByLineAndColumn) {
  TextGridOptions opt;
  opt.dx = 1e-4;
  const std::string longer = write_bytes("long.txt", "1 2\n3 4 5\n");
  const std::string e1 = refusal(longer, opt);
  std::filesystem::remove(longer);
  EXPECT_NE(e1.find("line 2, column 5 (field 3)"), std::string::npos) << e1;
  const std::string shorter = write_bytes("short.txt", "1 2 3\n\n  4;5\n");
  const std::string e2 = refusal(shorter, opt);
  std::filesystem::remove(shorter);
  EXPECT_NE(e2.find("line 3, column 5 (field 2): the line ends after 2 values"), std::string::npos) << e2;
  // Found by fuzz_text_grid: a line of separators only was a record without fields, whose
  // "last field" was index -1 (undefined behaviour). It is refused by line.
  const std::string commas = write_bytes("commas.txt", "1,2\n,\n3,4\n");
  const std::string e3 = refusal(commas, opt);
  std::filesystem::remove(commas);
  EXPECT_NE(e3.find("line 2, column 1: separators but no value"), std::string::npos) << e3;
}

TEST(Import, Hdf5RoundTripKeepsDataAndSpacing) {
  HeightMap m(5, 3, 1e-4, 2e-4);
  m.periodic = true;
  for (std::size_t i = 0; i < m.h.size(); ++i) m.h[i] = std::sin(double(i)) * 1e-4;
  double mean = 0;
  for (double v : m.h) mean += v;
  mean /= m.h.size();
  const std::string path = temp_path("rt.h5");
  write_surface_file(path, m, std::nullopt, nlohmann::json::object());
  const LoadedSurface s = load_surface(path);
  std::filesystem::remove(path);
  ASSERT_EQ(s.map.nx, 5u);
  ASSERT_EQ(s.map.ny, 3u);
  EXPECT_EQ(s.map.dx, 1e-4);
  EXPECT_EQ(s.map.dy, 2e-4);
  EXPECT_TRUE(s.map.periodic);
  for (std::size_t i = 0; i < m.h.size(); ++i) EXPECT_NEAR(s.map.h[i], m.h[i] - mean, 1e-18);
}

TEST(Import, DropoutFillIsTheMeanOfValidNeighboursLayerByLayer) {
  HeightMap m(5, 5, 1, 1);
  m.periodic = false;
  for (std::size_t iy = 0; iy < 5; ++iy)
    for (std::size_t ix = 0; ix < 5; ++ix) m(ix, iy) = double(ix);  // a ramp in x
  // A 3x3 hole in the middle: the ring fills first from outside, then the centre.
  for (std::size_t iy = 1; iy < 4; ++iy)
    for (std::size_t ix = 1; ix < 4; ++ix) m(ix, iy) = NAN;
  EXPECT_EQ(fill_dropouts(m), 9u);
  // Layer 1: (1,1) sees (0,1)=0 and (1,0)=1 -> 0.5; (2,1) sees (2,0)=2 -> 2; (3,1): (4,1)=4,(3,0)=3 -> 3.5
  EXPECT_DOUBLE_EQ(m(1, 1), 0.5);
  EXPECT_DOUBLE_EQ(m(2, 1), 2.0);
  EXPECT_DOUBLE_EQ(m(3, 1), 3.5);
  EXPECT_DOUBLE_EQ(m(1, 2), 0.0);
  EXPECT_DOUBLE_EQ(m(3, 2), 4.0);
  // Layer 2: the centre takes the mean of its four filled neighbours: (2 + 0 + 4 + 2) / 4.
  EXPECT_DOUBLE_EQ(m(2, 2), 2.0);
}

TEST(Import, PeriodicMapsLoseOnlyTheirMean) {
  HeightMap m(8, 8, 1e-3, 1e-3);
  m.periodic = true;
  for (std::size_t iy = 0; iy < 8; ++iy)
    for (std::size_t ix = 0; ix < 8; ++ix) m(ix, iy) = 1.0 + 0.1 * double(ix);  // one period of a sawtooth
  const MeanPlane p = remove_mean_plane(m, std::vector<unsigned char>(64, 0));
  EXPECT_EQ(p.tilt_x, 0.0);
  EXPECT_NEAR(p.offset, 1.35, 1e-12);
}

// How a `unit` string attribute reaches /height: the encodings h5py writes (variable length
// UTF-8, the default for str; fixed-length null-padded for numpy bytes 'S2'; either as a
// one-element array when given a list) and those C-API writers choose (null-terminated, space
// padded, ASCII variable length).
struct UnitEncoding {
  const char* name;
  bool variable;
  H5T_cset_t cset;
  H5T_str_t pad;
  std::size_t size;  // fixed length only
  bool array;        // a one-element array instead of a scalar
};

// A 4 x 4 periodic map of heights +-1 (in the file's unit) with `unit` written as `e`.
void write_map_with_unit(const std::string& path, const std::string& unit, const UnitEncoding& e) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {4, 4};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t ds = H5Dcreate2(f, "/height", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  double h[16];
  for (int i = 0; i < 16; ++i) h[i] = ((i + i / 4) % 2) ? 1.0 : -1.0;  // a checkerboard: rms 1 unit
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, h);
  const double dx = 1e-4;
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t adx = H5Acreate2(ds, "dx", H5T_IEEE_F64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(adx, H5T_NATIVE_DOUBLE, &dx);
  H5Aclose(adx);
  const long one = 1;
  const hid_t aper = H5Acreate2(ds, "periodic", H5T_STD_I64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(aper, H5T_NATIVE_LONG, &one);
  H5Aclose(aper);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_cset(type, e.cset);
  const hsize_t one_elem = 1;
  const hid_t aspace = e.array ? H5Screate_simple(1, &one_elem, nullptr) : H5Screate(H5S_SCALAR);
  if (e.variable) {
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t a = H5Acreate2(ds, "unit", type, aspace, H5P_DEFAULT, H5P_DEFAULT);
    const char* p = unit.c_str();
    H5Awrite(a, type, &p);
    H5Aclose(a);
  } else {
    H5Tset_size(type, e.size);
    H5Tset_strpad(type, e.pad);
    std::string buf = unit;
    buf.resize(e.size, e.pad == H5T_STR_SPACEPAD ? ' ' : '\0');
    const hid_t a = H5Acreate2(ds, "unit", type, aspace, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, buf.data());
    H5Aclose(a);
  }
  H5Sclose(aspace);
  H5Tclose(type);
  H5Sclose(scalar);
  H5Dclose(ds);
  H5Sclose(space);
  H5Fclose(f);
}

double rms(const HeightMap& m) {
  double s = 0;
  for (double v : m.h) s += v * v;
  return std::sqrt(s / double(m.h.size()));
}

const UnitEncoding kUnitEncodings[] = {
    {"h5py str (variable, UTF-8)", true, H5T_CSET_UTF8, H5T_STR_NULLTERM, 0, false},
    {"h5py str in a list (variable, UTF-8, 1-element array)", true, H5T_CSET_UTF8, H5T_STR_NULLTERM, 0, true},
    {"variable, ASCII", true, H5T_CSET_ASCII, H5T_STR_NULLTERM, 0, false},
    {"h5py numpy bytes (fixed, null-padded, exact size)", false, H5T_CSET_ASCII, H5T_STR_NULLPAD, 2, false},
    {"fixed, null-padded, UTF-8, longer than the text", false, H5T_CSET_UTF8, H5T_STR_NULLPAD, 8, false},
    {"C API (fixed, null-terminated)", false, H5T_CSET_ASCII, H5T_STR_NULLTERM, 3, false},
    {"fixed, space-padded", false, H5T_CSET_ASCII, H5T_STR_SPACEPAD, 6, false},
};

TEST(Import, HeightUnitIsReadInEveryStringEncoding) {
  const std::string path = temp_path("unit.h5");
  for (const UnitEncoding& e : kUnitEncodings) {
    write_map_with_unit(path, "mm", e);
    const LoadedSurface s = load_surface(path);
    EXPECT_NEAR(rms(s.map), 1e-3, 1e-15) << e.name;  // 1 mm, not 1 m
  }
  // The micro sign in UTF-8, as instruments write it.
  write_map_with_unit(path, "\u00b5m", kUnitEncodings[0]);
  EXPECT_NEAR(rms(load_surface(path).map), 1e-6, 1e-18);
  std::filesystem::remove(path);
}

TEST(Import, UnknownHeightUnitIsRefusedByName) {
  const std::string path = temp_path("furlong.h5");
  for (const UnitEncoding& e : {kUnitEncodings[0], kUnitEncodings[5]}) {
    write_map_with_unit(path, "in", e);
    try {
      load_surface(path);
      FAIL() << e.name;
    } catch (const InputError& err) {
      EXPECT_NE(std::string(err.what()).find("unknown height unit 'in'"), std::string::npos) << err.what();
      EXPECT_NE(std::string(err.what()).find(path), std::string::npos) << err.what();
    }
  }
  std::filesystem::remove(path);
}

// Found by make fuzz: a /synthesis record whose seed or oversample does not fit an integer was
// cast anyway (undefined behaviour); it is refused, naming the attribute.
TEST(Import, SynthesisRecordWithOutOfRangeIntegersIsRefused) {
  const std::string path = temp_path("synthesis.h5");
  HeightMap m(4, 4, 1e-3, 1e-3);
  m.periodic = true;
  for (std::size_t i = 0; i < m.h.size(); ++i) m.h[i] = 1e-4 * double(i % 3);
  SynthesisRecord rec;
  rec.oversample = 1;
  write_surface_file(path, m, rec, nlohmann::json::object());
  for (const auto& [name, v] : {std::pair<const char*, double>{"oversample", 8.8e12}, {"seed", -1.0}, {"oversample", 1.5}}) {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t g = H5Gopen2(f, "/synthesis", H5P_DEFAULT);
    const hid_t a = H5Aopen(g, name, H5P_DEFAULT);
    const hid_t space = H5Aget_space(a);
    H5Aclose(a);
    H5Adelete(g, name);
    const hid_t b = H5Acreate2(g, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(b, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(b);
    H5Sclose(space);
    H5Gclose(g);
    H5Fclose(f);
    try {
      load_surface(path);
      FAIL() << name << " = " << v;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("attribute ") + name + " is not a whole number"), std::string::npos)
          << e.what();
    }
    write_surface_file(path, m, rec, nlohmann::json::object());
  }
  std::filesystem::remove(path);
}

// Found by make fuzz: a hole surrounded by heights near the largest double filled itself with
// Inf (the neighbours' sum overflowed), which never counted as filled: the fill looped forever.
TEST(Import, DropoutFillNearTheLargestDoubleEnds) {
  HeightMap m(3, 3, 1, 1);
  m.periodic = false;
  for (double& v : m.h) v = 1.5e308;
  m(1, 1) = NAN;
  EXPECT_EQ(fill_dropouts(m), 1u);
  EXPECT_DOUBLE_EQ(m(1, 1), 1.5e308);
}

}  // namespace
}  // namespace wr
