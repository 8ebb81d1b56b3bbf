// `wetroad compound` (issue 56, part 1): DMA isotherms generated from a known compound and shift
// law, with 1 % noise, must give back the law's constants, the shift factors and the friction;
// bad data is refused by file, line or column.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lib/core/errors.hpp"
#include "lib/friction/compound.hpp"
#include "lib/friction/dma_data.hpp"
#include "lib/friction/friction_scene.hpp"
#include "lib/friction/hysteresis_friction.hpp"
#include "lib/friction/master_curve.hpp"
#include "tests/cli_fixture.hpp"

namespace wr {
namespace {

// The DMA file a lab would send for `truth`: isotherms t0, t0 + step, ..., t1 (deg C), 12
// frequencies log-spaced over 0.1-30 Hz, E' and E'' in MPa with relative Gaussian noise.
std::string dma_csv(const Compound& truth, double t0, double t1, double step, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::ostringstream o;
  o.precision(10);
  o << "temperature [C],frequency [Hz],E' [MPa],E'' [MPa]\n";
  for (double t = t0; t <= t1 + 1e-9; t += step)
    for (int k = 0; k < 12; ++k) {
      const double f = 0.1 * std::pow(300.0, k / 11.0);
      const std::complex<double> e = truth.modulus(2 * M_PI * f, t);
      o << t << "," << f << "," << e.real() * (1 + noise * gauss(rng)) / 1e6 << "," << e.imag() * (1 + noise * gauss(rng)) / 1e6
        << "\n";
    }
  return o.str();
}

double max_friction_difference(const Compound& a, const Compound& b) {
  const RoughnessSpectrum psd = band_spectrum(1e3, 1e5, 1e-22);
  FrictionOptions opt;
  double worst = 0;
  for (int i = 0; i < 10; ++i) {
    const double v = 1e-4 * std::pow(1e5, i / 9.0);  // 1e-4 ... 10 m/s
    const double ma = hysteresis_friction(psd, a, v, opt).mu, mb = hysteresis_friction(psd, b, v, opt).mu;
    worst = std::max(worst, std::abs(mb / ma - 1));
  }
  return worst;
}

TEST(CompoundFromDma, WlfRoundTrip) {
  const Compound truth = read_compound_json(default_compound_path());
  const DmaData d = parse_dma_csv(dma_csv(truth, -30, 60, 5, 0.01, 7), "generated.csv");
  ASSERT_EQ(d.isotherms.size(), 19u);
  MasterCurveOptions opt;
  opt.reference_temperature = truth.reference_temperature;
  const MasterCurve m = build_master_curve(d, opt);
  EXPECT_NEAR(m.c1 / truth.wlf_c1, 1.0, 0.02);  // bar: 2 %
  EXPECT_NEAR(m.c2 / truth.wlf_c2, 1.0, 0.02);
  for (const ShiftRow& r : m.shifts) EXPECT_NEAR(r.log_at, truth.log10_shift(r.temperature), 0.05) << r.temperature;  // bar: 0.05 decades
  const Compound back = compound_from_master(m, "round trip", "test", truth.poisson);
  EXPECT_LT(max_friction_difference(truth, back), 0.02);  // bar: mu(v) within 2 % at 10 speeds
  ASSERT_TRUE(m.glass_transition.has_value());
  EXPECT_NEAR(*m.glass_transition, -25, 3);  // the compound's stated Tg (its "name": about -25 C)
}

TEST(CompoundFromDma, ArrheniusRoundTrip) {
  Compound truth = read_compound_json(default_compound_path());
  truth.arrhenius_energy = 120e3;  // J/mol
  const DmaData d = parse_dma_csv(dma_csv(truth, -30, 60, 5, 0.01, 11), "generated.csv");
  MasterCurveOptions opt;
  opt.law = ShiftLaw::arrhenius;
  opt.reference_temperature = 20;
  const MasterCurve m = build_master_curve(d, opt);
  EXPECT_NEAR(m.activation_energy / 120e3, 1.0, 0.02);  // bar: 2 %
  const Compound back = compound_from_master(m, "round trip", "test", truth.poisson);
  ASSERT_TRUE(back.arrhenius_energy.has_value());
  EXPECT_LT(max_friction_difference(truth, back), 0.02);
  // written and read back as a compound file
  const Compound again = parse_compound_json(compound_to_json(back).dump(), "again");
  EXPECT_EQ(again.arrhenius_energy, back.arrhenius_energy);
  EXPECT_DOUBLE_EQ(again.log10_shift(-10), back.log10_shift(-10));
}

TEST(CompoundFromDma, ShearModuliAndUnits) {
  // G' and G'' in kPa, temperatures in K, frequencies in rad/s: the same Young's moduli (3 G).
  const std::string e = "temperature [C],frequency [Hz],E' [MPa],E'' [MPa]\n20,1,3,0.3\n20,2,3.3,0.33\n20,4,3.6,0.36\n"
                        "30,1,2.9,0.29\n30,2,3.1,0.31\n30,4,3.4,0.34\n";
  const std::string g = "T [K],f [rad/s],G' [kPa],G'' [kPa]\n293.15,6.283185307179586,1000,100\n293.15,12.566370614359172,1100,110\n"
                        "293.15,25.132741228718345,1200,120\n303.15,6.283185307179586,966.6666666666666,96.66666666666667\n"
                        "303.15,12.566370614359172,1033.3333333333333,103.33333333333333\n303.15,25.132741228718345,1133.3333333333333,113.33333333333333\n";
  const DmaData a = parse_dma_csv(e, "e.csv"), b = parse_dma_csv(g, "g.csv");
  ASSERT_EQ(b.isotherms.size(), 2u);
  EXPECT_TRUE(b.shear);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(b.isotherms[i].storage[k] / a.isotherms[i].storage[k], 1.0, 1e-12);
      EXPECT_NEAR(b.isotherms[i].omega[k] / a.isotherms[i].omega[k], 1.0, 1e-12);
      EXPECT_NEAR(b.isotherms[i].temperature, a.isotherms[i].temperature, 1e-9);
    }
}

std::string refusal(const std::string& text) {
  try {
    build_master_curve(parse_dma_csv(text, "lab.csv"), {});
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CompoundFromDma, BadDataIsRefusedByLineOrColumn) {
  const std::string head = "temperature [C],frequency [Hz],E' [MPa],E'' [MPa]\n";
  const std::string iso20 = "20,1,3,0.3\n20,3,3.3,0.33\n20,10,3.6,0.36\n";
  // isotherms that do not overlap: 0 C lies 6 decades of frequency from 20 C
  const Compound truth = read_compound_json(default_compound_path());
  EXPECT_NE(refusal(dma_csv(truth, -40, 20, 30, 0.0, 1)).find("do not overlap"), std::string::npos);
  // E' falling with frequency: the line named
  const std::string falling = refusal(head + iso20 + "30,1,3,0.3\n30,3,2,0.33\n30,10,3.6,0.36\n");
  EXPECT_NE(falling.find("lab.csv:6"), std::string::npos) << falling;
  EXPECT_NE(falling.find("E' falls with frequency"), std::string::npos) << falling;
  // negative modulus: the line and column
  const std::string negative = refusal(head + iso20 + "30,1,3,-0.3\n");
  EXPECT_NE(negative.find("lab.csv:5"), std::string::npos) << negative;
  EXPECT_NE(negative.find("E'' [MPa]"), std::string::npos) << negative;
  // a missing unit, and a temperature without its unit (Celsius or Fahrenheit?)
  EXPECT_NE(refusal("temperature [C],frequency [Hz],E',E'' [MPa]\n").find("\"E'\" has no unit"), std::string::npos);
  EXPECT_NE(refusal("temperature,frequency [Hz],E' [MPa],E'' [MPa]\n" + iso20).find("\"temperature\" has no unit"), std::string::npos);
  EXPECT_NE(refusal("temperature [R],frequency [Hz],E' [MPa],E'' [MPa]\n").find("not C, K or F"), std::string::npos);
  // Fahrenheit is read when it says so: 68 F is 20 C
  const DmaData f = parse_dma_csv("temperature [F],frequency [Hz],E' [MPa],E'' [MPa]\n68,1,3,0.3\n68,3,3.3,0.33\n68,10,3.6,0.36\n"
                                  "86,1,2.9,0.29\n86,3,3.2,0.32\n86,10,3.5,0.35\n", "f.csv");
  EXPECT_NEAR(f.isotherms[0].temperature, 20, 1e-9);
  // one isotherm, a row of the wrong width, a non-number, a frequency twice
  EXPECT_NE(refusal(head + iso20).find("2 or more temperatures"), std::string::npos);
  EXPECT_NE(refusal(head + iso20 + "30,1,3\n").find("lab.csv:5"), std::string::npos);
  EXPECT_NE(refusal(head + iso20 + "30,1,three,0.3\n").find("not a finite number"), std::string::npos);
  EXPECT_NE(refusal(head + iso20 + "30,1,3,0.3\n30,1,3.1,0.3\n30,3,3.2,0.3\n").find("frequency given twice"), std::string::npos);
  EXPECT_NE(refusal("temperature [C],frequency [Hz],E' [MPa],G'' [MPa]\n").find("both be Young's"), std::string::npos);
}

using wr_test::Cli;
using wr_test::CliRun;
namespace fs = std::filesystem;
class CompoundCli : public Cli {};

TEST_F(CompoundCli, WritesACompoundTheFrictionModelReadsAndRefusesBadData) {
  const Compound truth = read_compound_json(default_compound_path());
  std::ofstream(path("lab.csv")) << dma_csv(truth, -30, 60, 5, 0.01, 3);
  const CliRun ok = run("compound " + path("lab.csv") + " -o " + path("c.json") + " --plots " + path("charts"));
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("glass transition"), std::string::npos);
  for (const char* f : {"master-storage.svg", "master-loss.svg", "master-tan-delta.svg", "shift-factors.svg"})
    EXPECT_TRUE(fs::exists(path("charts") + "/" + f)) << f;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("c.json")));
  EXPECT_EQ(j["dma"]["shifts"].size(), 19u);
  EXPECT_FALSE(j["synthetic"].get<bool>());
  ASSERT_EQ(run("synth --size 32 --dx 1e-4 -q -o " + path("s.h5")).code, 0);
  const CliRun f = run("friction " + path("s.h5") + " --compound " + path("c.json") + " --speeds 1 --no-film -q");
  EXPECT_EQ(f.code, 0) << f.err;
  std::ofstream(path("bad.csv")) << "temperature,frequency [Hz],E' [MPa],E'' [MPa]\n20,1,3,0.3\n";
  const CliRun bad = run("compound " + path("bad.csv") + " -o " + path("b.json"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("bad.csv"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(fs::exists(path("b.json")));
  EXPECT_EQ(run("compound " + path("lab.csv") + " -o " + path("x.json") + " --shift-law williams").code, 2);
  EXPECT_EQ(run("compound " + path("lab.csv") + " -o " + path("x.json") + " --reference-temperature 200").code, 2);
}

}  // namespace
}  // namespace wr
