// libFuzzer: the measured skid numbers of `report --measured` (site,mpd_mm,sn40r[,speed_kmh]).
#include "reports/html_report.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = wr::fuzz::as_file(data, size, "sites.csv");
  wr::fuzz::expect_clean([&] { wr::read_measured_skid_csv(path); });
  return 0;
}
