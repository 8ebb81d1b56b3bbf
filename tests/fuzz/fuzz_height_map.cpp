// libFuzzer: an HDF5 height map (/height or /profile, dx, dy, unit) through load_surface.
#include "roads/surface_import.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = wr::fuzz::as_file(data, size, "map.h5");
  wr::fuzz::expect_clean([&] { wr::load_surface(path); });
  return 0;
}
