// End-to-end: the wetroad binary on good and bad input (exit codes, messages, no stray output).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/cli_fixture.hpp"

namespace {

using namespace wr_test;
namespace fs = std::filesystem;

TEST_F(Cli, HelpAndVersion) {
  CliRun r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("synth"), std::string::npos);
  EXPECT_NE(r.out.find("analyze"), std::string::npos);
  r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("wetroad"), std::string::npos);
  r = run("synth --help");
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--size", "--dx", "--h0", "--hurst", "--q0-ratio", "--q1", "--q1-fraction", "--oversample", "--seed"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  r = run("analyze --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--json"), std::string::npos);
}

TEST_F(Cli, SynthThenAnalyzeWritesEveryDocumentedKey) {
  const std::string s = path("s.h5"), j = path("a.json"), o = path("a.h5");
  CliRun r = run("synth --size 128 --dx 1e-4 --h0 5e-4 --hurst 0.8 --seed 3 -o " + s);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("analyze " + s + " --json " + j + " --out " + o);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("prescribed"), std::string::npos);
  EXPECT_NE(r.out.find("non-standard baseline"), std::string::npos);
  std::ifstream f(j);
  const auto js = nlohmann::json::parse(f);
  for (const char* key : {"nx", "ny", "dx", "dy", "h0", "sa", "ssk", "sku", "rms_slope_spectral", "rms_slope_fd", "rms_slope_central", "m0",
                          "m2", "m4", "alpha", "hurst_fit", "q0_fit", "plateau_fit", "summit_density", "summit_mean",
                          "summit_var", "mpd", "mpd_std", "etd", "kappa_persson", "kappa_bgt"}) {
    ASSERT_TRUE(js.contains(key)) << key;
    EXPECT_TRUE(js[key].is_number()) << key;
  }
  ASSERT_TRUE(js.contains("prescribed"));
  EXPECT_NEAR(js["prescribed"]["h0"].get<double>(), 5e-4, 1e-15);
  EXPECT_NEAR(js["h0"].get<double>() / 5e-4, 1.0, 1e-9);
  EXPECT_NEAR(js["prescribed"]["hurst_fit"].get<double>(), 0.8, 1e-15);
  EXPECT_TRUE(js["prescribed"]["mpd"].is_number());
  EXPECT_EQ(js["nx"].get<int>(), 128);
  EXPECT_TRUE(fs::exists(o));
}

TEST_F(Cli, SynthIsBitIdenticalAcrossRuns) {
  ASSERT_EQ(run("synth --size 64 --seed 9 -o " + path("a.h5")).code, 0);
  ASSERT_EQ(run("synth --size 64 --seed 9 -o " + path("b.h5")).code, 0);
  // Compare the height datasets through analyze's JSON would be indirect; read the raw maps.
  auto read = [&](const std::string& p) {
    const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/height", H5P_DEFAULT);
    std::vector<double> v(64 * 64);
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(d);
    H5Fclose(f);
    return v;
  };
  EXPECT_EQ(read(path("a.h5")), read(path("b.h5")));
}

TEST_F(Cli, SynthRefusesQ1AboveNyquistAndSuggestsOversampling) {
  const CliRun r = run("synth --size 100 --dx 1e-4 --q1 62831.85 -o " + path("s.h5"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--oversample 2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("s.h5")));
  EXPECT_EQ(run("synth --size 100 --dx 1e-4 --q1 62831.85 --oversample 2 -o " + path("s.h5")).code, 0);
}

TEST_F(Cli, SynthRefusesAGridThatDoesNotFitInMemory) {
  const CliRun r = run("synth --size 4000000 -o " + path("s.h5"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("memory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("s.h5")));
}

TEST_F(Cli, FillWritesTheWetSurfaceAndItsSummary) {
  const std::string s = path("s.h5"), w = path("w.h5"), j = path("w.json");
  ASSERT_EQ(run("synth --size 64 --seed 2 -o " + s).code, 0);
  CliRun r = run("fill " + s + " --coverage 0.2 -o " + w + " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(j);
  const auto js = nlohmann::json::parse(f);
  for (const char* key : {"coverage", "rain_depth", "stored_volume", "drained_volume", "lakes", "mean_depth",
                          "max_depth", "mode", "tiling", "connectivity"})
    EXPECT_TRUE(js.contains(key)) << key;
  EXPECT_NEAR(js["coverage"].get<double>(), 0.2, 1.0 / 4096 + 1e-12);
  // The wet surface is itself a surface analyze accepts.
  r = run("analyze " + w + " --json " + path("a.json"));
  EXPECT_EQ(r.code, 0) << r.err;
  r = run("fill " + s + " --limit --tiling 3x3 -o " + path("t.h5"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("3x3"), std::string::npos);
}

TEST_F(Cli, FillRefusesBadRequests) {
  const std::string s = path("s.h5");
  ASSERT_EQ(run("synth --size 32 -o " + s).code, 0);
  for (const std::string args : {"--rain -1", "--rain nan", "--coverage 0.999", "--coverage 1.5", "", "--rain 1e-4 --limit",
                                 "--rain 1e-4 --connectivity 6", "--limit --stagnant", "--rule cap"}) {
    const CliRun r = run("fill " + s + " " + args + " -o " + path("w.h5"));
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(path("w.h5"))) << args;
  }
}

TEST_F(Cli, ContactRunsAShearTestAndReportsEveryStep) {
  const std::string s = path("s.h5"), j = path("c.json");
  ASSERT_EQ(run("synth --size 12 --q0-ratio 2 --dx 1e-4 --h0 2e-5 --seed 4 -o " + s).code, 0);
  CliRun r = run("contact --surface " + s + " --problem shear --uz 1e-4 --ux 2e-5 --steps 1 --refine 1 --json " + j +
                 " --out " + path("c.h5") + " --vtu " + path("c.vtu"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("c.h5")));
  EXPECT_TRUE(fs::exists(path("c.vtu")));
  std::ifstream f(j);
  const auto js = nlohmann::json::parse(f);
  for (const char* key : {"model", "nodes", "dofs", "ranks", "wall_s"}) EXPECT_TRUE(js.contains(key)) << key;
  ASSERT_EQ(js["steps"].size(), 2u);  // one normal, one shear step
  for (const char* key : {"uz", "ux", "fz", "fx", "fy", "area_fraction", "contact_area", "sigma_star", "mu", "separation",
                          "max_penetration", "signorini_iterations", "linear_iterations", "wall_s"})
    EXPECT_TRUE(js["steps"][1].contains(key)) << key;
  EXPECT_GT(js["steps"][0]["fz"].get<double>(), 0.0);
  ASSERT_TRUE(js.contains("peak"));  // one shear step: it is the peak
  EXPECT_EQ(js["peak"]["step"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(js["peak"]["mu"].get<double>(), js["steps"][1]["mu"].get<double>());
  EXPECT_FALSE(js["peak"]["reached"].get<bool>());  // nothing after it: a lower bound only
  // Whether mu settled is measured and judged: the shear step's drift and mu per Signorini
  // iteration, and the "friction converged" check beside the others.
  EXPECT_TRUE(js["steps"][1]["mu_drift"].is_number());
  EXPECT_EQ(js["steps"][1]["mu_history"].size(), js["steps"][1]["signorini_iterations"].get<std::size_t>());
  EXPECT_TRUE(js["steps"][0]["mu_drift"].is_null());  // a normal step's mu is not judged
  // Slow-mode jumps are counted per step: at most one per block of 5 iterations, none in the first.
  for (const auto& st : js["steps"]) {
    ASSERT_TRUE(st["extrapolations"].is_number_integer());
    EXPECT_GE(st["extrapolations"].get<int>(), 0);
    EXPECT_LE(st["extrapolations"].get<int>(), std::max(0, st["signorini_iterations"].get<int>() / 5 - 1));
  }
  bool judged = false;
  for (const auto& v : js["validity"]["checks"]) judged |= v["check"] == "friction converged";
  EXPECT_TRUE(judged) << js["validity"].dump();
  // Failure is never a number: an iteration cap that cannot be met ends with exit code 3, the
  // residual history, and the finished steps labelled.
  r = run("contact --surface " + s + " --problem normal --uz 1e-4 --steps 2 --refine 1 --tol 1e-30 --max-iterations 3 --json " + j);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
  std::ifstream g(j);
  const auto jf = nlohmann::json::parse(g);
  EXPECT_EQ(jf["status"], "failed");
  // A step that meets --tol but leaves a node deeper in the obstacle than --max-penetration
  // is a failure too, never a number. The iteration goes on while the node comes out (here it
  // would reach 1e-15 m in ~20 iterations), so the cap ends it still too deep.
  r = run("contact --surface " + s + " --problem normal --uz 1e-4 --steps 1 --refine 1 --tol 0.5 --max-penetration 1e-15 --max-iterations 12 --json " + j);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("penetration"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("obstacle slope"), std::string::npos) << r.err;  // where, and how steep there
  EXPECT_NE(r.err.find("deeper than the allowed"), std::string::npos) << r.err;
  r = run("contact --surface " + s + " --problem normal --uz 1e-4 --extrapolate 1");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--extrapolate"), std::string::npos) << r.err;
  r = run("contact --surface " + s + " --problem normal --uz 1e-4 --cutbacks -1");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--cutbacks"), std::string::npos) << r.err;
  r = run("contact --surface " + path("nope.h5") + " --uz 1e-4");
  EXPECT_EQ(r.code, 2);
}

// Load-step cutback: the press to 0.4 mm needs 22 Signorini iterations in one step and 19 in
// each of two halves (measured), so a cap of 20 fails the single step; with --cutbacks 1 the
// step is retried from the unloaded block as two halves, and both the half-way state and the
// end agree with a run asked for two steps (to the iteration's tolerance: the retry starts from
// the same state but its round-off path differs).
TEST_F(Cli, ContactCutbackRetriesAFailedStepInTwoHalves) {
  const std::string s = path("s.h5"), once = path("once.json"), cut = path("cut.json"), two = path("two.json");
  ASSERT_EQ(run("synth --size 12 --q0-ratio 2 --dx 1e-4 --h0 2e-5 --seed 4 -o " + s).code, 0);
  // AMG-preconditioned CG: with it the capped single step fails (the direct solve converges).
  const std::string press = "contact --surface " + s + " --problem normal --uz 4e-4 --refine 1 --tol 1e-6 --solver amg ";
  CliRun r = run(press + "--steps 1 --max-iterations 20 --json " + once);
  ASSERT_EQ(r.code, 3) << r.err;  // without cutbacks the capped single step fails
  r = run(press + "--steps 1 --max-iterations 20 --cutbacks 1 --json " + cut);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("(cut back)"), std::string::npos) << r.out;
  ASSERT_EQ(run(press + "--steps 2 --json " + two).code, 0);
  std::ifstream fc(cut), ft(two);
  const auto jc = nlohmann::json::parse(fc), jt = nlohmann::json::parse(ft);
  ASSERT_EQ(jc["steps"].size(), 2u);
  EXPECT_EQ(jc["steps"][0]["failed_attempts"].get<int>(), 1);
  EXPECT_EQ(jc["steps"][1]["failed_attempts"].get<int>(), 0);
  for (int k = 0; k < 2; ++k) {
    EXPECT_DOUBLE_EQ(jc["steps"][k]["uz"].get<double>(), jt["steps"][k]["uz"].get<double>());
    EXPECT_NEAR(jc["steps"][k]["fz"].get<double>() / jt["steps"][k]["fz"].get<double>(), 1.0, 1e-5) << k;
    EXPECT_NEAR(jc["steps"][k]["area_fraction"].get<double>(), jt["steps"][k]["area_fraction"].get<double>(), 1e-9) << k;
  }
}

TEST_F(Cli, ContactSpectralModelReportsEveryStep) {
  const std::string s = path("s.h5"), j = path("sp.json");
  ASSERT_EQ(run("synth --size 64 --q0-ratio 2 --dx 1e-4 --h0 2e-5 --seed 4 -o " + s).code, 0);
  CliRun r = run("contact --model spectral --surface " + s + " --uz 1e-4 --steps 3 --json " + j + " --out " + path("sp.h5"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("sp.h5")));
  std::ifstream f(j);
  const auto js = nlohmann::json::parse(f);
  EXPECT_EQ(js["model"], "spectral");
  for (const char* key : {"nodes", "dofs", "ranks", "wall_s", "thickness"}) EXPECT_TRUE(js.contains(key)) << key;
  ASSERT_EQ(js["steps"].size(), 3u);
  double last_area = 0, last_fz = 0;
  for (const auto& st : js["steps"]) {
    EXPECT_TRUE(st["converged"].get<bool>());
    EXPECT_GT(st["fz"].get<double>(), last_fz);  // a deeper approach carries more load ...
    EXPECT_GE(st["area_fraction"].get<double>(), last_area);  // ... on a larger contact
    last_fz = st["fz"].get<double>();
    last_area = st["area_fraction"].get<double>();
  }
  EXPECT_NEAR(js["steps"][2]["uz"].get<double>(), 1e-4, 1e-15);  // displacement control
  // The half-space is load-controlled: the mean pressure comes back as Fz / A0.
  r = run("contact --model spectral --thickness inf --pressure 1e-3 --steps 1 --surface " + s + " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream g(j);
  const auto jh = nlohmann::json::parse(g);
  const double a0 = std::pow(64 * 1e-4, 2);
  EXPECT_NEAR(jh["steps"][0]["fz"].get<double>() / (1e-3 * a0), 1.0, 1e-12);
  // Bad combinations are one-line errors with exit code 2; an iteration cap is a failure (3).
  // The shear test (a layer pressed by --uz): per-step mu and the peak.
  r = run("contact --model spectral --problem shear --uz 1e-4 --ux 5e-5 --steps 1 --shear-steps 2 --surface " + s +
          " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream sh(j);
  const auto js2 = nlohmann::json::parse(sh);
  ASSERT_EQ(js2["steps"].size(), 3u);
  EXPECT_TRUE(js2.contains("peak"));
  EXPECT_GT(js2["steps"][2]["signorini_iterations"].get<int>(), 1);  // the geometry iteration ran
  for (const char* bad : {"--thickness inf --uz 1e-4", "--thickness -1 --uz 1e-4", "--uz 1e-4 --pressure 1",
                          "--pressure 1 --problem shear --ux 1e-4", "--thickness inf --pressure 1 --problem shear --ux 1e-4",
                          "--uz 1e-4 --problem shear"}) {
    r = run(std::string("contact --model spectral --surface ") + s + " " + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
  r = run("contact --model spectral --surface " + s + " --uz 1e-4 --steps 1 --max-iterations 2 --json " + j);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
}

// The mesh-convergence bench refuses bad input with one line and exit code 2 before any mesh.
TEST_F(Cli, MeshConvergenceBenchRefusesBadInput) {
  const std::string s = path("mc.h5");
  ASSERT_EQ(run("synth --size 16 --q0-ratio 2 --dx 1e-4 --h0 5e-6 --seed 4 -o " + s).code, 0);
  for (const std::string& bad : {"--surface " + path("missing.h5"), "--surface " + s + " --refines 4 2",
                                "--surface " + s + " --uz -1", "--surface " + s + " --refines 0 1 2"}) {
    const CliRun r = run("bench mesh-convergence " + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
}

// The analytic model's curve through the thesis's quartic fit (eq. 5.4): Persson's
// erf(sqrt 2 s) = sqrt(8/pi) s - (4 sqrt 2 / (3 sqrt pi)) s^3 + ..., so kappa and Omega are known.
TEST_F(Cli, AnalyticModelReportsTheAreaLoadFits) {
  const std::string s = path("s.h5"), j = path("an.json");
  ASSERT_EQ(run("synth --size 32 --q0-ratio 2 --dx 1e-4 --h0 5e-6 --seed 4 -o " + s).code, 0);
  const CliRun r = run("contact --model analytic --pressure 2e-3 --steps 6 --surface " + s + " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(j);
  const auto js = nlohmann::json::parse(f);
  const auto& q = js["area_load_fit"]["quartic"];
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(q["kappa"].get<double>(), std::sqrt(8 / pi), 1e-4);
  EXPECT_NEAR(q["Omega"].get<double>(), -4 * std::sqrt(2.0) / (3 * std::sqrt(pi)), 1e-2);
  EXPECT_TRUE(js["area_load_fit"].contains("yam"));
  // The low-pressure regression (sec. 5.2.3) over the steps below 15 % contact: erf is concave,
  // so its chord slope lies just under sqrt(8/pi), by 2 s^2 / 3 < 1 % for s below 0.1.
  const auto& low = js["area_load_fit"]["low_pressure"];
  EXPECT_GE(low["points"].get<int>(), 2);
  EXPECT_LT(low["kappa"].get<double>(), std::sqrt(8 / pi));
  EXPECT_GT(low["kappa"].get<double>(), 0.99 * std::sqrt(8 / pi));
}

// sigma* can be normalised by either slope estimate; the JSON gives kappa for both, and they
// differ by exactly the slopes' ratio (kappa = A/A0 / sigma*, sigma* ~ 1 / slope).
TEST_F(Cli, SpectralContactGivesKappaForTheCentralDifferenceSlopeToo) {
  const std::string s = path("s.h5"), j = path("sp.json");
  ASSERT_EQ(run("synth --size 64 --dx 1e-4 --h0 1e-5 --seed 2 -o " + s).code, 0);
  const CliRun r = run("contact --model spectral --thickness inf --pressure 2e-3 --steps 3 --surface " + s +
                       " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("with sigma* over the central-difference slope"), std::string::npos) << r.out;
  std::ifstream f(j);
  const auto js = nlohmann::json::parse(f);
  const double fwd = js["rms_slope"].get<double>(), cen = js["rms_slope_central"].get<double>();
  EXPECT_LT(cen, fwd);  // the central stencil damps the short waves
  EXPECT_GT(cen, 0.5 * fwd);
  const auto& low = js["area_load_fit"]["low_pressure"];
  ASSERT_GE(low["points"].get<int>(), 1);
  EXPECT_NEAR(low["kappa_central_slope"].get<double>() / low["kappa"].get<double>(), cen / fwd, 1e-12);
}

TEST_F(Cli, ContactAutoModelSaysWhichChecksDecided) {
  const std::string s = path("s.h5"), j = path("auto.json");
  ASSERT_EQ(run("synth --size 64 --q0-ratio 2 --dx 1e-4 --h0 5e-6 --seed 4 -o " + s).code, 0);  // gentle
  // Low pressure: the analytic model answers, and the checks are in the JSON.
  CliRun r = run("contact --model auto --pressure 1e-4 --steps 1 --surface " + s + " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("model auto: analytic"), std::string::npos) << r.err;
  std::ifstream f(j);
  auto js = nlohmann::json::parse(f);
  EXPECT_EQ(js["model"], "analytic");
  EXPECT_TRUE(js["validity"]["valid"].get<bool>());
  EXPECT_EQ(js["validity"]["chosen_by"], "auto");
  // Friction: only the FEM; a spectral shear test asked for by name is flagged, not silent.
  r = run("contact --model spectral --problem shear --uz 1e-5 --ux 1e-5 --steps 1 --shear-steps 1 --surface " + s +
          " --json " + j);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: outside the spectral model's validity (lateral finiteness)"), std::string::npos) << r.err;
  std::ifstream g(j);
  js = nlohmann::json::parse(g);
  EXPECT_FALSE(js["validity"]["valid"].get<bool>());
  // Nothing can answer a pressure-controlled shear test on a steep surface: an error, exit 2.
  ASSERT_EQ(run("synth --size 32 --q0-ratio 2 --dx 1e-4 --h0 1e-4 --seed 4 -o " + path("steep.h5")).code, 0);
  r = run("contact --model auto --pressure 1 --problem shear --ux 1e-4 --surface " + path("steep.h5"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no model passes its validity checks"), std::string::npos) << r.err;
}

TEST_F(Cli, MissingFile) { expect_bad_input(path("nope.h5"), "no such file"); }

TEST_F(Cli, NotHdf5) {
  std::ofstream(path("text.h5")) << "this is not HDF5\n";
  expect_bad_input(path("text.h5"), "not an HDF5 file");
}

TEST_F(Cli, NoHeightDataset) {
  make_h5("other.h5", "/elevation", {4, 4}, 1e-4);
  expect_bad_input(path("other.h5"), "no /height");
}

TEST_F(Cli, WrongRank) {
  make_h5("rank3.h5", "/height", {3, 4, 5}, 1e-4);
  expect_bad_input(path("rank3.h5"), "rank 3");
  make_h5("rank1.h5", "/height", {40}, 1e-4);
  expect_bad_input(path("rank1.h5"), "/profile");
}

TEST_F(Cli, NonPositiveSpacing) {
  make_h5("dx0.h5", "/height", {8, 8}, 0.0);
  expect_bad_input(path("dx0.h5"), "dx must be a positive");
  make_h5("dxneg.h5", "/height", {8, 8}, -1e-4);
  expect_bad_input(path("dxneg.h5"), "dx must be a positive");
  make_h5("nodx.h5", "/height", {8, 8}, std::nullopt);
  expect_bad_input(path("nodx.h5"), "no dx attribute");
}

TEST_F(Cli, AllNaN) {
  make_h5("nan.h5", "/height", {8, 8}, 1e-4, true, NAN);
  expect_bad_input(path("nan.h5"), "every sample is a dropout");
}

TEST_F(Cli, OneByOne) {
  make_h5("one.h5", "/height", {1, 1}, 1e-4);
  expect_bad_input(path("one.h5"), "at least 2x2");
}

TEST_F(Cli, DimensionThatDoesNotFitInMemory) {
  make_h5("huge.h5", "/height", {1u << 20, 1u << 20}, 1e-4, false);  // 8 TiB declared, nothing stored
  expect_bad_input(path("huge.h5"), "memory");
}

TEST_F(Cli, ProfileAndTextInputsWork) {
  make_h5("prof.h5", "/profile", {4000}, 1e-4);
  CliRun r = run("analyze " + path("prof.h5") + " --json " + path("p.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(path("p.json"));
  const auto js = nlohmann::json::parse(f);
  EXPECT_TRUE(js["summit_density"].is_null());
  EXPECT_TRUE(js["mpd"].is_number());
  std::ofstream(path("g.txt")) << "0 1 0 1\n1 0 1 0\n0 1 0 1\n";
  r = run("analyze " + path("g.txt") + " --dx 1e-4 --unit mm");
  EXPECT_EQ(r.code, 0) << r.err;
  r = run("analyze " + path("g.txt"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--dx"), std::string::npos) << r.err;
}

}  // namespace
