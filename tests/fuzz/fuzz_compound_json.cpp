// libFuzzer: a rubber compound file (`--compound`, lib/friction/compound.hpp): a Prony series or
// a measured master-curve table, parsed from memory (parse_compound_json; the file variant only
// adds the read). A compound that loads is also evaluated once, as the friction model will: a
// file the reader accepts must give a finite modulus, not NaN further down.
#include <cmath>

#include "lib/friction/compound.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  wr::fuzz::expect_clean([&] {
    const wr::Compound c = wr::parse_compound_json(text, "compound.json");
    for (const double omega : {0.0, 1.0, 1e6})
      if (!std::isfinite(std::abs(c.modulus_at_reference(omega)))) __builtin_trap();
  });
  return 0;
}
