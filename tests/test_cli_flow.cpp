// End-to-end: `wetroad flow` on a synthesized surface (elastic and rigid gaps, both solvers, the
// .vti and JSON outputs) and its refusals of bad input (exit code 2, one line naming the option,
// no output written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/cli_fixture.hpp"

namespace {

using namespace wr_test;
namespace fs = std::filesystem;

class FlowCli : public Cli {
 protected:
  void SetUp() override {
    Cli::SetUp();  // the scratch folder
    const CliRun r = run("synth --size 64 --dx 1e-4 --h0 1e-5 --hurst 0.8 --seed 2 -o " + path("s.h5"));
    ASSERT_EQ(r.code, 0) << r.err;
  }
  nlohmann::json read_json(const std::string& name) const {
    std::ifstream f(path(name));
    return nlohmann::json::parse(f);
  }
  void expect_refused(const std::string& args, const std::string& option) {
    const std::size_t before = count_files();
    const CliRun r = run("flow " + path("s.h5") + " " + args + " --json " + path("o.json") + " --vti " + path("o.vti"));
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(count_files(), before) << args << ": an output file appeared";
  }
};

TEST_F(FlowCli, ElasticGapGivesConductanceAndFields) {
  const CliRun r = run("flow " + path("s.h5") + " --pressure 2e4 --json " + path("f.json") + " --vti " + path("f.vti"));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* s : {"A/A0", "mean gap", "K (m^3)", "percolates in x", "cholmod", "timing", "contact", "flow"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  const nlohmann::json j = read_json("f.json");
  EXPECT_NEAR(j["mean_pressure"].get<double>(), 2e4, 1e-6);
  const double a = j["area_fraction"].get<double>();
  EXPECT_GT(a, 0.0);
  EXPECT_LT(a, 0.4);
  EXPECT_TRUE(j["percolates_x"].get<bool>() && j["percolates_y"].get<bool>());
  const auto& k = j["conductance"];
  EXPECT_GT(k["kxx"].get<double>(), 0);
  EXPECT_GT(k["kyy"].get<double>(), 0);
  EXPECT_NEAR(k["kxy"].get<double>(), k["kyx"].get<double>(), 1e-9 * k["kxx"].get<double>());
  // Contact can only obstruct: the flow factor at the mean gap is below the plates'.
  EXPECT_LT(j["flow_factor"]["xx"].get<double>(), 1.0);
  EXPECT_EQ(j["solver"], "cholmod");
  EXPECT_TRUE(j["provenance"].contains("timings"));
  std::ifstream v(path("f.vti"), std::ios::binary);
  std::string head(300, '\0');
  v.read(head.data(), 300);
  EXPECT_NE(head.find("ImageData"), std::string::npos);
  EXPECT_NE(head.find("WholeExtent=\"0 63 0 63 0 0\""), std::string::npos);
  EXPECT_GT(fs::file_size(path("f.vti")), 6u * 64 * 64 * 8);  // six Float64 arrays
}

TEST_F(FlowCli, AmgAgreesWithCholmod) {
  ASSERT_EQ(run("flow " + path("s.h5") + " --pressure 2e4 --json " + path("d.json")).code, 0);
  const CliRun r = run("flow " + path("s.h5") + " --pressure 2e4 --solver amg --tol 1e-12 --json " + path("a.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json d = read_json("d.json"), a = read_json("a.json");
  EXPECT_EQ(a["solver"], "amg");
  const double scale = d["conductance"]["kxx"].get<double>();
  for (const char* c : {"kxx", "kyy", "kxy"})
    EXPECT_NEAR(a["conductance"][c].get<double>() / scale, d["conductance"][c].get<double>() / scale, 1e-8) << c;
}

TEST_F(FlowCli, RigidFlatAtAContactFractionOrSeparation) {
  ASSERT_EQ(run("flow " + path("s.h5") + " --rigid --contact-fraction 0.3 --json " + path("r.json")).code, 0);
  const nlohmann::json j = read_json("r.json");
  EXPECT_NEAR(j["area_fraction"].get<double>(), 1229.0 / 4096, 1e-12);  // round(0.3 N) highest points
  EXPECT_TRUE(j["mean_pressure"].is_null());
  const double u = j["mean_gap"].get<double>();
  char sep[32];
  std::snprintf(sep, sizeof sep, "%.17g", u);
  ASSERT_EQ(run("flow " + path("s.h5") + " --rigid --separation " + sep + " --json " + path("u.json")).code, 0);
  EXPECT_NEAR(read_json("u.json")["mean_gap"].get<double>() / u, 1.0, 1e-9);
  // Past the percolation threshold nothing flows in any direction: refused in one line naming
  // the surface, nothing written (the library's K = 0 there: test_flow).
  const CliRun none = run("flow " + path("s.h5") + " --rigid --contact-fraction 0.9 --json " + path("c.json"));
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("no drainage in any direction"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("s.h5"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(path("c.json")));
}

TEST_F(FlowCli, BadInputIsOneLineNamingTheOption) {
  expect_refused("--pressure 0", "--pressure");
  expect_refused("--pressure -3e5", "--pressure");
  expect_refused("--nu 0.5", "--nu");
  expect_refused("--E 0", "--E");
  expect_refused("--solver direct", "--solver");
  expect_refused("--tol 0", "--tol");
  expect_refused("--rigid", "--rigid");
  expect_refused("--rigid --contact-fraction 1.5", "--contact-fraction");
  expect_refused("--rigid --contact-fraction 0.3 --separation 1e-6", "--rigid");
  expect_refused("--rigid --separation -1e-6", "--separation");
  expect_refused("--rigid --contact-fraction 0.3 --pressure 1e5", "--pressure");
  expect_refused("--contact-fraction 0.3", "--contact-fraction");
  const std::size_t before = count_files();
  const CliRun r = run("flow " + path("missing.h5") + " --json " + path("o.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing.h5"), std::string::npos) << r.err;
  EXPECT_EQ(count_files(), before);
}

}  // namespace
