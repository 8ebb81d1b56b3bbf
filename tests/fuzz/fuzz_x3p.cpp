// libFuzzer: X3P archives through the surface loader, two ways. Raw bytes as the archive (zip
// structure, CRCs); and, for an input starting with '<', the bytes as main.xml zipped here with
// a fixed 4 x 3 float64 data file and a correct md5checksum.hex, so that mutations reach the XML
// reader and the format's rules instead of stopping at the zip's checksums.
#include <zip.h>

#include <cstring>

#include "lib/core/content_hash.hpp"
#include "roads/surface_import.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

std::string zipped_main_xml(const std::uint8_t* data, std::size_t size) {
  static const double heights[12] = {1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4, 7e-4, 8e-4, 9e-4, 1e-3, 1.1e-3, 1.2e-3};
  const std::string xml(reinterpret_cast<const char*>(data), size);
  const std::string bin(reinterpret_cast<const char*>(heights), sizeof heights);  // little-endian host
  const std::string sum = wr::md5_hex(xml) + " *main.xml\n";
  const std::string valid("\xff\x0f", 2);
  const std::string path = wr::fuzz::scratch_dir() + "/built.x3p";
  int err = 0;
  zip_t* za = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  if (!za) __builtin_trap();
  for (const auto* e : {&xml, &bin, &sum, &valid}) {
    const char* name = e == &xml ? "main.xml" : e == &bin ? "bindata/data.bin" : e == &sum ? "md5checksum.hex" : "bindata/valid.bin";
    zip_source_t* s = zip_source_buffer(za, e->data(), e->size(), 0);
    if (!s || zip_file_add(za, name, s, 0) < 0) __builtin_trap();
  }
  if (zip_close(za) != 0) __builtin_trap();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = size > 0 && data[0] == '<' ? zipped_main_xml(data, size)
                                                      : wr::fuzz::as_file(data, size, "surface.x3p");
  wr::fuzz::expect_clean([&] { wr::load_surface(path); });
  return 0;
}
