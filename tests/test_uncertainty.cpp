// The skid number's band (lib/friction/uncertainty.hpp, issue 56 bar 4): against brute-force
// evaluation at the corners of a two-input range, and the tornado against direct evaluations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lib/friction/compound.hpp"
#include "lib/friction/friction_scene.hpp"
#include "lib/friction/uncertainty.hpp"

namespace wr {
namespace {

SkidInputs inputs() {
  SkidInputs in;
  in.dry = in.hysteresis = band_spectrum(1e3, 1e5, 3e-21);  // rms ~ 20 um
  in.compound = read_compound_json(default_compound_path());
  in.film.test = tyre_test("e274-ribbed");
  in.options.threads = 1;
  return in;
}

TEST(SkidBand, TwoInputBandLiesWithinTheCornersAndReachesThem) {
  const SkidInputs in = inputs();
  UncertaintySetup u;
  u.ranges = {{"pressure", 0.2e6, 0.4e6, false}, {"temperature", 10, 30, false}};
  u.samples = 64;
  const SkidBand b = skid_number_band(in, u);
  // brute force: the four corners
  std::vector<double> corners;
  for (double p : {0.2e6, 0.4e6})
    for (double t : {10.0, 30.0}) corners.push_back(skid_number_at(in, {{"pressure", p}, {"temperature", t}}));
  const double lo = *std::min_element(corners.begin(), corners.end()), hi = *std::max_element(corners.begin(), corners.end());
  // SN is monotone in each input over these ranges (checked at the midlines), so the box's
  // extremes are at its corners and every sample lies between them
  const double mid = skid_number_at(in, {{"pressure", 0.3e6}, {"temperature", 20}});
  EXPECT_GE(mid, lo);
  EXPECT_LE(mid, hi);
  for (double s : b.samples) {
    EXPECT_GE(s, lo - 1e-9 * std::abs(lo));
    EXPECT_LE(s, hi + 1e-9 * std::abs(hi));
  }
  // 64 strata per input: the sample extremes come within a tenth of the range of the corners'
  EXPECT_LT(b.min - lo, 0.1 * (hi - lo));
  EXPECT_LT(hi - b.max, 0.1 * (hi - lo));
  EXPECT_LE(b.p05, b.p95);
  EXPECT_GE(b.p05, b.min);
  EXPECT_LE(b.p95, b.max);
  EXPECT_NEAR(b.nominal, skid_number_at(in, {}), 1e-12);
  EXPECT_EQ(b.evaluations, 1 + 2 * 2 + 64);
}

TEST(SkidBand, TornadoRowsAreTheOneAtATimeEvaluations) {
  const SkidInputs in = inputs();
  UncertaintySetup u;
  u.ranges = default_ranges(in);
  u.samples = 8;
  ASSERT_EQ(u.ranges.size(), 5u);  // the default compound is synthetic: its master curve's shift is a range
  const SkidBand b = skid_number_band(in, u);
  for (std::size_t i = 0; i < b.tornado.size(); ++i) {
    const TornadoRow& t = b.tornado[i];
    EXPECT_DOUBLE_EQ(t.sn_low, skid_number_at(in, {{t.name, t.low}})) << t.name;
    EXPECT_DOUBLE_EQ(t.sn_high, skid_number_at(in, {{t.name, t.high}})) << t.name;
    if (i > 0) {
      EXPECT_LE(std::abs(t.sn_high - t.sn_low), std::abs(b.tornado[i - 1].sn_high - b.tornado[i - 1].sn_low));
    }
  }
  EXPECT_THROW(skid_number_at(in, {{"humidity", 1}}), std::invalid_argument);
}

}  // namespace
}  // namespace wr

#include <nlohmann/json.hpp>

#include "tests/cli_fixture.hpp"

namespace wr {
namespace {

using wr_test::Cli;
using wr_test::CliRun;
class BandCli : public Cli {};

// The sweeps' --band: each run records its skid-number band; the report's summary shows it
// beside the spread over realizations.
TEST_F(BandCli, SweepRunsCarryTheirBandIntoTheSummary) {
  const CliRun s = run("sweep-roughness --dataset A --values 1e-4 --realizations 2 --size 64 --model hysteresis --band --out " +
                       path("g.h5") + " --json " + path("g.json") + " -q");
  ASSERT_EQ(s.code, 0) << s.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("g.json")));
  for (const auto& r : j["runs"]) {
    const auto& b = r["contact"]["sn_band"];
    EXPECT_LE(b["min"].get<double>(), b["p05"].get<double>());
    EXPECT_LE(b["p05"].get<double>(), b["p95"].get<double>());
    EXPECT_LE(b["p95"].get<double>(), b["max"].get<double>());
  }
  ASSERT_EQ(run("report --sweep " + path("g.h5") + " -o " + path("r.html")).code, 0);
  EXPECT_NE(slurp(path("r.html")).find("inputs 5-95 %"), std::string::npos);
  EXPECT_EQ(run("sweep-roughness --dataset A --values 1e-4 --size 16 --model hysteresis --band --no-film --out " + path("x.h5")).code, 2);
}

}  // namespace
}  // namespace wr
