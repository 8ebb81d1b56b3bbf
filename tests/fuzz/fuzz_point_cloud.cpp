// libFuzzer: an x y z point cloud (text) triangulated and gridded (CGAL Delaunay).
#include "roads/surface_import.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = wr::fuzz::as_file(data, size, "cloud.xyz");
  wr::TextGridOptions opt;
  opt.dx = 1e-3;
  opt.points = true;
  opt.unit_scale = 1e-3;
  wr::fuzz::expect_clean([&] { wr::load_surface(path, opt); });
  return 0;
}
