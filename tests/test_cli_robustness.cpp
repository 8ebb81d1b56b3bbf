// End-to-end: inputs are never destroyed, outputs appear all together or not at all, absurd
// sizes and non-finite results are refused, every option is validated before any work.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/cli_fixture.hpp"

namespace {

using namespace wr_test;
namespace fs = std::filesystem;

class Robust : public Cli {
 protected:
  void SetUp() override {
    Cli::SetUp();
    ASSERT_EQ(run("synth --size 16 --dx 1.875e-3 --h0 1e-4 --seed 3 -q -o " + path("a.h5")).code, 0);
  }

  std::string bytes(const std::string& p) const { return slurp(p); }

  // Exit 2, one line on stderr naming `needle`, and the scratch folder exactly as before.
  void expect_refused(const std::string& args, const std::string& needle) {
    const std::size_t before = count_entries();
    const std::string input = bytes(path("a.h5"));
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(count_entries(), before) << args << ": something was written";
    EXPECT_EQ(bytes(path("a.h5")), input) << args << ": the input changed";
  }

  // Files and folders, hidden staging files included.
  std::size_t count_entries() const {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.path().filename() != "stdout.txt" && e.path().filename() != "stderr.txt";
    return n;
  }

  const std::string kSweep = " --coverages 0 --uz 1e-3 --ux 1e-3 --steps 1 --shear-steps 1 --model spectral -q";
  const std::string kSpectral = " --model spectral --uz 1e-5 --steps 1 -q";
};

TEST_F(Robust, AnOutputThatIsAnInputIsRefusedBeforeAnyWork) {
  const std::string a = path("a.h5");
  fs::create_directories(path("sub"));
  fs::create_symlink(a, path("link.h5"));
  expect_refused("analyze " + a + " --json " + a, "is an input");
  expect_refused("analyze " + a + " --out " + path("sub/../a.h5"), "is an input");  // another spelling
  expect_refused("fill " + a + " --limit -o " + path("link.h5"), "is an input");     // a link to it
  expect_refused("fill " + path("link.h5") + " --limit -o " + a, "is an input");
  expect_refused("contact --surface " + a + kSpectral + " --json " + a, "is an input");
  expect_refused("contact --surface " + a + " --wet " + path("link.h5") + kSpectral + " --out " + a, "is an input");
  expect_refused("report --sweep " + a + " -o " + a, "is an input");
  expect_refused("sweep-coverage --surface " + a + kSweep + " --out " + a, "is an input");
  expect_refused("sweep-coverage --surface " + a + kSweep + " --out " + path("s.h5") + " --csv " + path("./a.h5"),
                 "is an input");
  expect_refused("synth --scene " + path("scene.json") + " -o " + path("scene.json"), "is an input");
  // Two outputs of one command on one file.
  expect_refused("analyze " + a + " --json " + path("o") + " --out " + path("o"), "is also the output of --json");
  expect_refused("sweep-coverage --surface " + a + kSweep + " --out " + path("s.h5") + " --json " + path("s.h5"),
                 "is also the output");
}

TEST_F(Robust, OutputsAppearAllTogetherOrNotAtAll) {
  const std::string a = path("a.h5"), missing = path("no-such-dir/x");
  std::ofstream(path("plain-file")) << "x";
  expect_refused("analyze " + a + " --json " + path("ok.json") + " --out " + missing, "does not exist");
  expect_refused("fill " + a + " --limit -o " + path("ok.h5") + " --json " + missing, "does not exist");
  expect_refused("contact --surface " + a + kSpectral + " --json " + path("ok.json") + " --out " + missing,
                 "does not exist");
  expect_refused("contact --surface " + a + " --uz 1e-5 --steps 1 -q --json " + path("ok.json") + " --vtu " + missing,
                 "does not exist");
  expect_refused("synth --size 16 -o " + path("ok.h5") + " --json " + path("plain-file/x.json"), "not a directory");
  expect_refused("report --sweep " + a + " -o " + missing, "does not exist");
  expect_refused("sweep-coverage --surface " + a + kSweep + " --out " + path("s.h5") + " --plots " +
                     path("plain-file/charts"),
                 "--plots");
  EXPECT_FALSE(fs::exists(path("s.h5.runs"))) << "the sweep started";
  // A writable set: every output appears, and no staging file is left.
  const CliRun r = run("sweep-coverage --surface " + a + kSweep + " --out " + path("s.h5") + " --csv " + path("s.csv") +
                       " --plots " + path("charts"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("s.h5")) && fs::exists(path("s.csv")) && fs::exists(path("charts/mu_ratio.svg")));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_NE(e.path().filename().string().find(".tmp-"), 0u) << "staging left: " << e.path();
}

TEST_F(Robust, AbsurdSizesAreRefusedBeforeAllocation) {
  const std::string a = path("a.h5");
  expect_refused("contact --surface " + a + " --uz 1e-5 --steps 2000000000", "--steps");
  expect_refused("contact --surface " + a + kSpectral + " --problem shear --ux 1e-5 --shear-steps 2000000000",
                 "--steps");
  expect_refused("contact --surface " + a + " --uz 1e-5 --steps 1 --refine 1000", "--refine");
  expect_refused("sweep-coverage --surface " + a + kSweep + " --max-iterations 2000000000 --out " + path("s.h5"),
                 "--max-iterations");
  expect_refused("synth --size 4000000000 -o " + path("b.h5"), "--size");
}

TEST_F(Robust, NonFiniteResultsAreErrorsNotFiles) {
  const CliRun s = run("synth --size 16 --dx 1e300 -o " + path("b.h5"));
  EXPECT_EQ(s.code, 3) << s.err;
  EXPECT_NE(s.err.find("non-finite"), std::string::npos) << s.err;
  EXPECT_FALSE(fs::exists(path("b.h5")));
  // An rms height of 1e300 m no longer gets as far: it is refused as no road texture (issue 54).
  expect_refused("synth --size 16 --h0 1e300 -o " + path("b.h5"), "no road texture");
  const CliRun r = run("contact --surface " + path("a.h5") + " --model spectral --uz 1e300 --steps 4 -q --json " +
                       path("c.json"));
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("non-finite"), std::string::npos) << r.err;
  std::ifstream f(path("c.json"));
  EXPECT_EQ(nlohmann::json::parse(f)["status"], "failed");
}

TEST_F(Robust, ContactAndSweepsShareOneValidatorRunBeforeAnyWork) {
  const std::string a = path("a.h5");
  const std::string fem = "contact --surface " + a + " --uz 1e-5 --steps 1 ";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--tol nan", "--tol"},           {"--tol 0", "--tol"},
      {"--damping nan", "--damping"},   {"--problem shear --ux nan", "--ux"},
      {"--height -1", "--height"},      {"--max-iterations -1", "--max-iterations"},
      {"--facet-band 2", "--facet-band"}, {"--ksp-rtol nan", "--ksp-rtol"},
      {"--max-penetration nan", "--max-penetration"}, {"--E inf", "--E"},
      {"--curvature 2", "--curvature"}, {"--iteration newton --facet-normals", "--iteration"},
      {"--iteration newton --solver gmg", "--solver"}, {"--solver multigrid", "--solver"},
      {"--to-peak", "--to-peak"}};
  for (const auto& [opt, name] : bad) {
    expect_refused(fem + opt, name);
    // The sweeps take the same options and refuse the same values with the same words.
    // (--to-peak is refused here for want of a shear phase, which every sweep has; newton with facet
    // normals contradicts only within the FEM, and kSweep runs the spectral model.)
    if (opt.find("ksp") == std::string::npos && opt.find("problem") == std::string::npos &&
        opt.find("to-peak") == std::string::npos && opt.find("newton") == std::string::npos)
      expect_refused("sweep-coverage --surface " + a + kSweep + " " + opt + " --out " + path("s.h5"), name);
  }
  // Synthesis options of a sweep: refused before the sweep starts, with no checkpoint left.
  expect_refused("sweep-coverage --size 16 --hurst 1.5" + kSweep + " --out " + path("s.h5"), "--hurst");
  expect_refused("sweep-roughness --dataset B --values 0.5 1.5 --size 16 --uz 1e-3 --ux 1e-3 --out " + path("r.h5"),
                 "--values");
  expect_refused("sweep-coverage --surface " + a + kSweep + " --count 0 --out " + path("s.h5"), "--count");
}

TEST_F(Robust, SmallerDefects) {
  const std::string a = path("a.h5");
  // A 1-D profile is not a map the water module or the contact scene can use.
  make_h5("profile.h5", "/profile", {64}, 1e-4);
  expect_refused("fill " + path("profile.h5") + " --limit -o " + path("w.h5"), "1-D profile");
  expect_refused("contact --surface " + path("profile.h5") + kSpectral, "1-D profile");
  expect_refused("sweep-coverage --surface " + path("profile.h5") + kSweep + " --out " + path("s.h5"), "1-D profile");
  // Heights far beyond a road's: a unit left out.
  make_h5("huge.h5", "/height", {8, 8}, 1e-4, true, 1e296);
  expect_refused("analyze " + path("huge.h5"), "not a road texture");
  // The MPD options of ISO 13473-1, refused by name.
  expect_refused("analyze " + a + " --spike-alpha -1", "--spike-alpha");
  expect_refused("analyze " + a + " --lowpass -1", "--lowpass");
  expect_refused("analyze " + a + " --mpd-method sideways", "--mpd-method");
  // A map of 99 % dropouts is analysed, with a warning.
  {
    const hsize_t dims[2] = {32, 32};
    make_h5("holes.h5", "/height", {32, 32}, 1e-4, true, NAN);
    const hid_t f = H5Fopen(path("holes.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t ds = H5Dopen2(f, "/height", H5P_DEFAULT);
    std::vector<double> h(dims[0] * dims[1], NAN);
    for (std::size_t i = 0; i < 10; ++i) h[i * 97] = 1e-4 * double(i % 3);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, h.data());
    H5Dclose(ds);
    H5Fclose(f);
  }
  CliRun r = run("analyze " + path("holes.h5") + " -q");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dropouts"), std::string::npos) << r.err;
  // A bad PETSc option: one line, exit 2 (not PETSc's trace).
  expect_refused("contact --surface " + a + " --uz 1e-5 --steps 1 -q --petsc \"-ksp_type nonexistent\"", "--petsc");
  // The IFI F60 needs both device constants.
  expect_refused("report --sweep " + a + " --ifi-a 0.05 -o " + path("r.html"), "--ifi");
  // A file that cannot be read is not "not an HDF5 file" (root reads everything: nothing to test).
  if (::geteuid() != 0) {
    fs::copy_file(a, path("locked.h5"));
    fs::permissions(path("locked.h5"), fs::perms::none);
    expect_refused("analyze " + path("locked.h5"), "cannot read");
  }
}

// What the fuzzers found in the scene reader (make fuzz): each once undefined behaviour or an
// uncaught exception ("internal error"), now a one-line error naming the file.
TEST_F(Robust, SceneFilesFoundByTheFuzzerAreRefusedCleanly) {
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"[1, 2]", "a scene file is a JSON object"},
      {"{\"surface\": 3}", "\"surface\" must be an object"},
      {"{\"surface\": {\"size\": 1.6e29}}", "\"size\" must be a whole number"},
      {"{\"surface\": {\"size\": 99999999999999999999}}", "whole number"},  // beyond uint64: a float
      {"{\"surface\": {\"seed\": -3}}", "\"seed\" is out of range"},
      {"{\"surface\": {\"size\": 15, \"dx\": 0, \"sampling\": \"thesis\"}}", "--dx"}};
  int k = 0;
  for (const auto& [text, needle] : scenes) {
    const std::string scene = path("scene" + std::to_string(k++) + ".json");
    std::ofstream(scene) << text;
    expect_refused("synth --scene " + scene + " -o " + path("b.h5"), needle);
  }
}

}  // namespace

// every bad input of `wetroad friction` is one line naming the file or option,
// exit 2, and no output.
TEST_F(Robust, FrictionRefusesBadInputByName) {
  const std::string out = " --json " + path("f.json") + " --out " + path("f.h5") + " --plot " + path("f.svg");
  auto compound = [&](const std::string& name, const std::string& body) {
    std::ofstream(path(name)) << body;
  };
  const std::string good_head = R"({"name": "x", "source": "test", "reference_temperature_c": 20,
    "wlf": {"c1": 8.86, "c2_k": 101.6}, "poisson": 0.5, )";
  compound("missing.json", R"({"name": "x", "source": "test", "reference_temperature_c": 20, "poisson": 0.5,
    "prony": {"e_relaxed_pa": 3e6, "terms": [{"tau_s": 1e-6, "de_pa": 1e8}]}})");
  compound("negative.json", good_head + R"("prony": {"e_relaxed_pa": 3e6, "terms": [{"tau_s": 1e-6, "de_pa": -1e8}]}})");
  // E' falling with frequency while E'' peaks: no causal material.
  compound("noncausal.json", good_head + R"("table": {"omega_rad_s": [1, 10, 100, 1000, 10000, 100000],
    "storage_pa": [1e9, 5e8, 1e8, 3e7, 1e7, 5e6], "loss_pa": [1e6, 1e7, 1e8, 1e8, 1e7, 1e6]}})");
  const std::string f = "friction " + path("a.h5") + out;
  std::size_t before = count_entries();
  expect_refused(f + " --compound " + path("missing.json"), "missing.json: missing key \"wlf\"");
  expect_refused(f + " --compound " + path("negative.json"), "negative.json: prony.terms[0].de_pa must be a modulus >= 0 Pa");
  expect_refused(f + " --compound " + path("noncausal.json"), "noncausal.json: table: not causal");
  expect_refused(f + " --compound " + path("absent.json"), "absent.json: cannot open the compound file");
  expect_refused(f + " --speeds 0.1 0", "--speeds: a sliding speed must be positive");
  expect_refused(f + " --speeds -1", "--speeds: a sliding speed must be positive");
  expect_refused(f + " --pressure 0", "--pressure: the nominal pressure must be a positive number");
  expect_refused(f + " --pressure -3e5", "--pressure");
  expect_refused(f + " --q1 10", "--q1: 10 1/m lies below the measured band of");
  expect_refused(f + " --temperature -90", "--temperature: the WLF shift has its pole");
  expect_refused(f + " --flash-temperature --compound " + path("negative.json"), "negative.json");
  EXPECT_EQ(count_entries(), before);
}

// The command end to end on a synthesized surface and its wet version: the JSON carries the
// documented keys, the wet curves lie below the dry one, the flash temperature lowers mu at speed.
TEST_F(Robust, FrictionDryAndWetEndToEnd) {
  ASSERT_EQ(run("synth --size 64 --dx 1e-4 --h0 3e-4 --seed 2 -q -o " + path("s.h5")).code, 0);
  ASSERT_EQ(run("fill " + path("s.h5") + " --limit -q -o " + path("w.h5")).code, 0);
  const CliRun r = run("friction " + path("s.h5") + " --wet " + path("w.h5") +
                       " --speeds 1e-3 0.1 17.9 --flash-temperature --json " + path("f.json") + " --out " + path("f.h5"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("f.json")));
  for (const char* key : {"model", "compound", "temperature", "pressure", "q0", "q1", "extrapolated", "flash_temperature",
                          "speeds", "peak", "sn64", "provenance", "validity", "wet", "q1_scan"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["model"], "hysteresis");
  EXPECT_TRUE(j["extrapolated"].get<bool>());
  ASSERT_EQ(j["speeds"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const double dry = j["speeds"][i]["mu"], hom = j["wet"]["homogeneous"]["speeds"][i]["mu"],
                 loc = j["wet"]["local"]["speeds"][i]["mu"];
    EXPECT_GT(dry, 0);
    EXPECT_LT(hom, dry);
    EXPECT_LT(loc, dry);
  }
  EXPECT_GT(j["speeds"][2]["temperature_rise"].get<double>(), 1.0);
  EXPECT_NEAR(j["sn64"].get<double>(), 100 * j["speeds"][2]["mu"].get<double>(), 1e-6 * j["sn64"].get<double>());
  EXPECT_TRUE(fs::exists(path("f.h5")));
}

// The sweeps' hysteresis rung: coverage and roughness sweeps in seconds; the contact scene's
// displacements are refused with it (and required without it).
TEST_F(Robust, SweepsTakeTheHysteresisModel) {
  const std::string cov = "sweep-coverage --size 64 --dx 4e-4 --h0 3e-4 --seed 4 --model hysteresis --coverages 0 0.3 0.6 --out ";
  const CliRun r = run(cov + path("c.h5") + " --json " + path("c.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("c.json")));
  ASSERT_EQ(j["table"].size(), 3u);
  double last = 1.0 + 1e-12;
  for (const auto& row : j["table"]) {
    const double local = row["mu_ratio"]["mean"], hom = row["mu_ratio_homogeneous"]["mean"];
    EXPECT_LT(local, last);
    EXPECT_LE(local, hom + 1e-12);
    last = local + 1e-12;
  }
  EXPECT_EQ(j["runs"][0]["contact"]["model"], "hysteresis");
  const CliRun g = run("sweep-roughness --dataset A --values 1e-4 3e-4 --realizations 2 --size 64 --model hysteresis --out " +
                       path("g.h5") + " --json " + path("g.json") + " -q");
  ASSERT_EQ(g.code, 0) << g.err;
  const nlohmann::json k = nlohmann::json::parse(slurp(path("g.json")));
  EXPECT_LT(k["table"][0]["mu_peak"]["mean"].get<double>(), k["table"][1]["mu_peak"]["mean"].get<double>());
  EXPECT_GT(k["runs"][0]["coverage"].get<double>(), 0.2);  // wetted to the drained limit
  expect_refused(cov + path("x.h5") + " --uz 1e-3 --ux 1e-3", "--uz: the hysteresis model has no block to displace");
  expect_refused("sweep-coverage --size 16 --dx 1e-3 --coverages 0 --out " + path("y.h5"), "--uz: required by the contact models");
}

// Every scene option from every command that runs a scene: --layers (bricks per in-plane
// spacing) through contact and both sweeps changes the block's node count and is recorded.
TEST_F(Robust, SceneOptionsReachEveryCommandThatRunsAScene) {
  const std::string scene = " --uz 5e-4 --ux 3e-4 --steps 1 --shear-steps 1 --refine 1 --tol 1e-3 --max-iterations 60";
  std::size_t nodes[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string layers = k == 0 ? " --layers 1" : " --layers 3";
    const CliRun c = run("contact --surface " + path("a.h5") + " --problem shear" + scene + layers + " -q --json " +
                         path("c" + std::to_string(k) + ".json"));
    ASSERT_EQ(c.code, 0) << c.err;
    const nlohmann::json j = nlohmann::json::parse(slurp(path("c" + std::to_string(k) + ".json")));
    EXPECT_EQ(j["provenance"]["parameters"]["layers_per_level"], k == 0 ? 1 : 3);
    nodes[k] = j["nodes"].get<std::size_t>();
  }
  EXPECT_LT(nodes[0], nodes[1]);
  const CliRun cov = run("sweep-coverage --surface " + path("a.h5") + " --coverages 0" + scene + " --layers 3 -q --out " +
                         path("s.h5") + " --json " + path("s.json"));
  ASSERT_EQ(cov.code, 0) << cov.err;
  const nlohmann::json s = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(s["spec"]["scene"]["layers_per_level"], 3);
  EXPECT_EQ(s["runs"][0]["contact"]["unknowns"].get<std::size_t>(), nodes[1]);
  const CliRun rough = run("sweep-roughness --dataset A --values 1e-4 --realizations 1 --size 16 --dx 1.875e-3 --seed 3" +
                           scene + " --layers 3 -q --out " + path("r.h5") + " --json " + path("r.json"));
  ASSERT_EQ(rough.code, 0) << rough.err;
  const nlohmann::json r = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_EQ(r["spec"]["scene"]["layers_per_level"], 3);
  EXPECT_EQ(r["runs"][0]["contact"]["unknowns"].get<std::size_t>(), nodes[1]);  // same 16 x 16 grid
}

// The flash temperature needs the compound's thermal data: refused before any work without it.
TEST_F(Robust, FlashTemperatureNeedsThermalData) {
  std::ofstream(path("cold.json")) << R"({"name": "no thermal", "source": "test", "reference_temperature_c": 20,
    "wlf": {"c1": 8.86, "c2_k": 101.6}, "poisson": 0.5,
    "prony": {"e_relaxed_pa": 3e6, "terms": [{"tau_s": 1e-6, "de_pa": 1e8}]}})";
  expect_refused("friction " + path("a.h5") + " --flash-temperature --compound " + path("cold.json") + " --json " +
                     path("f.json"),
                 "--flash-temperature: the compound \"no thermal\" has no \"thermal\" block");
}
