// Import: text grids, HDF5 round trip, dropout filling, mean-plane removal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace wr
