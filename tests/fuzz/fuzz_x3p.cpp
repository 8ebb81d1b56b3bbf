// libFuzzer: an X3P archive (zip of main.xml, bindata, checksums) through the surface loader.
#include "roads/surface_import.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = wr::fuzz::as_file(data, size, "surface.x3p");
  wr::fuzz::expect_clean([&] { wr::load_surface(path); });
  return 0;
}
