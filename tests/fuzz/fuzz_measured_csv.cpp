// libFuzzer: the measured skid numbers of `report --measured` (site,mpd_mm,sn40r[,speed_kmh],
// RFC 4180 quoting), parsed from memory (read_measured_skid_csv only adds the file read). What
// the reader accepts must be safe to print: every site name escaped for the HTML holds no markup
// character and no control byte other than tab and newline.
#include "reports/html_parts.hpp"
#include "reports/measured_csv.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  wr::fuzz::expect_clean([&] {
    for (const wr::MeasuredSkid& m : wr::parse_measured_skid_csv(text, "sites.csv"))
      for (const char c : wr::html::escape(m.site))
        if (c == '<' || c == '>' || c == '"' || c == '\'' || (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n'))
          __builtin_trap();
  });
  return 0;
}
