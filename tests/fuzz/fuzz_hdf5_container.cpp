// libFuzzer: raw bytes as an HDF5 file through load_surface. This mostly exercises Debian's
// libhdf5 (1.10.8) on corrupt containers, where it reads past its own buffers (see
// tests/sanitizers/asan.supp and docs/robustness.md); wetroad's reader logic is fuzzed by
// fuzz_height_map on well-formed containers. Run by `make fuzz-libhdf5`, not by `make fuzz`.
#include "roads/surface_import.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = wr::fuzz::as_file(data, size, "container.h5");
  wr::fuzz::expect_clean([&] { wr::load_surface(path); });
  return 0;
}
