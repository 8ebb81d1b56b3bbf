// Coverage sweep and report: the statistics against hand computations, the wet runs against the
// water module's own contract, and the report's numbers against the HDF5 they come from.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "lib/core/errors.hpp"
#include "lib/io/hdf5_file.hpp"
#include "lib/sweep/coverage_sweep.hpp"
#include "lib/sweep/roughness_sweep.hpp"
#include "lib/sweep/sample_statistics.hpp"
#include "reports/sweep_outputs.hpp"
#include "reports/html_report.hpp"
#include "roads/height_stats.hpp"

namespace wr {
namespace {

nlohmann::json record(int index, int realization, double target, double mu, double area, const char* status = "ok") {
  return {{"index", index},
          {"realization", realization},
          {"target", target},
          {"status", status},
          {"water", target == 0 ? "dry" : "drained"},
          {"coverage", target},
          {"mean_pool_depth", 1e-4 * target},
          {"wet_sq", 1e-4},
          {"contact", {{"mu_peak", mu}, {"area_at_peak", area}, {"area_normal", area}}}};
}

// A run record less its wall-clock times: what must be identical between repeated runs.
nlohmann::json without_timings(nlohmann::json r) {
  r.erase("wall");
  for (auto& st : r["contact"]["steps"]) st.erase("wall_s");
  return r;
}

TEST(CoverageSweep, PlanIsRealizationMajor) {
  CoverageSweepSpec s;
  s.coverages = {0, 0.3};
  s.realizations = 2;
  const auto k = plan_runs(s);
  ASSERT_EQ(k.size(), 4u);
  EXPECT_EQ(k[1].realization, 0);
  EXPECT_EQ(k[1].target, 0.3);
  EXPECT_EQ(k[2].realization, 1);
  EXPECT_EQ(k[3].index, 3);
}

// mu_ratio is taken per realization, then averaged; the CI is t(0.975, n-1) s / sqrt(n).
TEST(CoverageSweep, TableStatisticsMatchHandComputation) {
  const std::vector<nlohmann::json> runs = {record(0, 0, 0, 0.4, 0.3),  record(1, 0, 0.5, 0.2, 0.35),
                                            record(2, 1, 0, 0.5, 0.3),  record(3, 1, 0.5, 0.4, 0.45),
                                            record(4, 2, 0, 0.5, 0.3),  record(5, 2, 0.5, 0.1, 0.5, "failed")};
  const nlohmann::json t = coverage_table(runs);
  ASSERT_EQ(t.size(), 2u);
  const auto& wet = t[1];
  EXPECT_EQ(wet["failed"].get<int>(), 1);
  EXPECT_EQ(wet["mu_ratio"]["n"].get<int>(), 2);
  // ratios 0.5 and 0.8: mean 0.65, s = 0.3/sqrt(2), CI = 12.706 s / sqrt(2)
  EXPECT_NEAR(wet["mu_ratio"]["mean"].get<double>(), 0.65, 1e-15);
  EXPECT_NEAR(wet["mu_ratio"]["std"].get<double>(), 0.3 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(wet["mu_ratio"]["ci95"].get<double>(), 12.706 * 0.3 / 2, 1e-12);
  EXPECT_NEAR(t[0]["mu_peak"]["mean"].get<double>(), 1.4 / 3, 1e-15);
  EXPECT_EQ(wet["runs"], nlohmann::json({1, 3, 5}));
  EXPECT_DOUBLE_EQ(student_t95(10), 2.228);
  EXPECT_NEAR(student_t95(200), 1.972, 2e-3);
}

// A run that cannot be done is a failed record with its key and reason, never an exception that
// would stop the other runs (or leave MPI ranks waiting).
TEST(CoverageSweep, AFailingRunIsARecordNotAnException) {
  CoverageSweepSpec s;
  s.surface_path = ::testing::TempDir() + "no-such-surface.h5";
  s.coverages = {0};
  s.scene.uz = s.scene.ux = 1e-3;
  CoverageRunner runner(s, MPI_COMM_NULL, 1);
  nlohmann::json r;
  ASSERT_NO_THROW(r = runner.run({0, 0, 0.0}));
  EXPECT_EQ(r["status"], "failed");
  EXPECT_NE(r["message"].get<std::string>().find("no-such-surface"), std::string::npos) << r["message"];
  const nlohmann::json t = coverage_table({r});
  EXPECT_EQ(t[0]["failed"].get<int>(), 1);
  EXPECT_EQ(t[0]["mu_peak"]["n"].get<int>(), 0);
}

TEST(CoverageSweep, BadSpecsAreRefused) {
  CoverageSweepSpec s;
  s.surface_path = "x.h5";
  s.scene.uz = 1e-3;
  s.scene.ux = 1e-3;
  s.coverages = {0.2, 0.1};
  EXPECT_THROW(check_sweep_spec(s), InputError);
  s.coverages = {0, 1.0};
  EXPECT_THROW(check_sweep_spec(s), InputError);
  s.coverages = {0, 0.5};
  s.realizations = 3;  // a file has one realization
  EXPECT_THROW(check_sweep_spec(s), InputError);
  s.realizations = 1;
  s.scene.model = ContactModel::analytic;  // no shear test
  EXPECT_THROW(check_sweep_spec(s), InputError);
}

CoverageSweepSpec small_spectral_sweep() {
  CoverageSweepSpec s;
  SynthParams p;
  p.nx = p.ny = 32;
  p.dx = 1e-3;
  p.h0 = 2e-4;
  p.seed = 4;
  s.synth = p;
  s.coverages = {0, 0.15, 0.9};
  s.scene.model = ContactModel::spectral;
  s.scene.uz = 2e-3;
  s.scene.ux = 1e-3;
  s.scene.normal_steps = 2;
  s.scene.shear_steps = 2;
  s.scene.tolerance = 1e-4;
  return s;
}

// Each run is the water module's fill of its target (drained below the drained limit, standing
// water above) under a real contact run; pools lower the wet surface's roughness.
TEST(CoverageSweep, RunsWetTheSurfaceAsTheWaterModuleSays) {
  const CoverageSweepSpec s = small_spectral_sweep();
  CoverageRunner runner(s, MPI_COMM_NULL, 1);
  const auto keys = plan_runs(s);
  std::vector<nlohmann::json> runs;
  for (const auto& k : keys) runs.push_back(runner.run(k));
  const double cell = 1.0 / (32 * 32);
  EXPECT_EQ(runs[0]["water"], "dry");
  EXPECT_EQ(runs[0]["status"], "ok") << runs[0]["message"];
  const double limit = runs[0]["drained_limit"].get<double>();
  ASSERT_GT(limit, 0.15);
  ASSERT_LT(limit, 0.9);
  EXPECT_EQ(runs[1]["water"], "drained");
  EXPECT_NEAR(runs[1]["coverage"].get<double>(), 0.15, 2 * cell);
  EXPECT_EQ(runs[2]["water"], "stagnant");
  EXPECT_NEAR(runs[2]["coverage"].get<double>(), 0.9, 2 * cell);
  EXPECT_GT(runs[2]["mean_pool_depth"].get<double>(), runs[1]["mean_pool_depth"].get<double>());
  EXPECT_LT(runs[2]["wet_sq"].get<double>(), runs[0]["wet_sq"].get<double>());
  for (const auto& r : runs) {
    EXPECT_EQ(r["contact"]["model"], "spectral");
    EXPECT_FALSE(r["contact"]["validity"]["valid"].get<bool>()) << "a periodic layer's friction must be flagged";
    EXPECT_EQ(r["contact"]["steps"].size(), 4u);
    EXPECT_GT(r["psd"]["q"].size(), 5u);
  }
  // The same run again (a fresh runner, as after a resume or on another rank): identical record.
  CoverageRunner again(s, MPI_COMM_NULL, 2);
  EXPECT_EQ(without_timings(again.run(keys[1])).dump(), without_timings(runs[1]).dump());
}

// The report's tables name their source run groups: each exists in the HDF5, and the printed
// ratios are the HDF5 table's values. The document is self-contained.
TEST(Report, EveryTableNumberTracesToTheHdf5) {
  const CoverageSweepSpec s = small_spectral_sweep();
  CoverageRunner runner(s, MPI_COMM_NULL, 1);
  std::vector<nlohmann::json> runs;
  for (const auto& k : plan_runs(s)) runs.push_back(runner.run(k));
  const nlohmann::json sweep = {{"spec", sweep_spec_json(s)}, {"table", coverage_table(runs)}, {"runs", runs},
                                {"failed_runs", 0}, {"provenance", {{"timings", {{"total", 1.0}, {"ranks", 1}}}}}};
  const std::string dir = ::testing::TempDir() + "wetroad-report-test";
  std::filesystem::create_directories(dir);
  const std::string h5 = dir + "/sweep.h5", html = dir + "/report.html";
  write_sweep_hdf5(h5, sweep, coverage_layout());
  ReportInput in;
  in.sweeps.emplace_back(h5, read_sweep_hdf5(h5, coverage_layout()));
  EXPECT_EQ(in.sweeps[0].second["table"], sweep["table"]);  // the HDF5 round trip is exact
  // A measured site whose name is markup, and a file name that is not UTF-8 with a line break:
  // the page shows them as text (issue 54, class 13).
  in.measured = {{"<script>alert('x')</script> & \"B\"", 0.8, 52, {}}};
  in.measured_path = "sites\xE9\nset output 'x'.csv";
  write_html_report(html, in);
  std::ifstream f(html);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  EXPECT_EQ(doc.find("<script"), std::string::npos);
  EXPECT_NE(doc.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;B&quot;"), std::string::npos);
  EXPECT_NE(doc.find("site (sites&#xFFFD;\nset output &#39;x&#39;.csv)"), std::string::npos);
  EXPECT_EQ(doc.find('\xE9'), std::string::npos);  // in the chart's legend too: U+FFFD, a blank
  EXPECT_FALSE(std::filesystem::exists("x"));
  EXPECT_EQ(doc.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(doc.find("</html>"), std::string::npos);
  EXPECT_EQ(doc.find("src="), std::string::npos) << "external resource";
  std::size_t svgs = 0;
  for (auto p = doc.find("<svg"); p != std::string::npos; p = doc.find("<svg", p + 1)) ++svgs;
  EXPECT_EQ(svgs, 5u);  // mu ratio, area, pool depth, wet PSD, skid numbers
  const std::regex href("href=['\"]([^'\"]*)['\"]");
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), href); it != std::sregex_iterator(); ++it)
    EXPECT_EQ((*it)[1].str().rfind("#", 0), 0u) << "non-local link " << (*it)[1].str();
  Hdf5Reader r(h5);
  const std::regex group("/runs/run-[0-9]{4}");
  std::set<std::string> named;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), group); it != std::sregex_iterator(); ++it)
    named.insert(it->str());
  EXPECT_EQ(named.size(), runs.size());
  for (const auto& g : named) EXPECT_TRUE(r.has_group(g)) << g;
  // The printed friction and ratios are the HDF5 table's (a ratio only where the dry mu is > 0).
  for (const auto& [column, format, scale] : {std::tuple{"/table/mu_peak", "<td>%.4g</td>", 1.0},
                                              std::tuple{"/table/mu_ratio", "<td>%.1f %%</td>", 100.0}}) {
    std::vector<double> v(r.dims(column)[0]);
    r.read_doubles(column, v.data(), v.size());
    for (double x : v) {
      if (!std::isfinite(x)) continue;
      char b[48];
      std::snprintf(b, sizeof b, format, scale * x);
      EXPECT_NE(doc.find(b), std::string::npos) << column << " " << b;
    }
  }
  std::filesystem::remove_all(dir);
}

// A thesis dataset on 32 x 32 surfaces over 3.2 cm with the spectral model: seconds, not hours.
RoughnessSweepSpec small_roughness_sweep(const std::string& dataset, std::vector<double> values, int realizations,
                                         int normal_steps) {
  RoughnessSweepSpec s = roughness_dataset(dataset);
  s.values = std::move(values);
  s.realizations = realizations;
  s.base.nx = s.base.ny = 32;
  s.base.dx = 1e-3;
  s.base.sampling = Sampling::nyquist;  // band-limited: h0 exact (aliasing keeps it only in expectation)
  s.scene.model = ContactModel::spectral;
  s.scene.uz = 1e-3;
  s.scene.ux = 1e-3;
  s.scene.normal_steps = normal_steps;
  s.scene.shear_steps = 1;
  return s;
}

// The thesis's datasets as Table 5.1 and D.1-D.3 state them, and their rows found by value.
TEST(RoughnessSweep, DatasetsAndThesisRows) {
  const RoughnessSweepSpec a = roughness_dataset("A");
  ASSERT_EQ(a.values.size(), 9u);
  EXPECT_NEAR(std::log10(a.values[5]), -3.52, 1e-12);
  EXPECT_EQ(a.base.nx, 300u);
  EXPECT_DOUBLE_EQ(a.base.dx, 1e-4);
  EXPECT_DOUBLE_EQ(a.base.q0_ratio, 5.0);
  EXPECT_EQ(a.base.sampling, Sampling::thesis);  // q1hat = 2 pi / dx, as Table 5.1
  EXPECT_EQ(roughness_dataset("B").values, (std::vector<double>{0.5, 0.6, 0.7, 0.8, 0.9}));
  EXPECT_EQ(roughness_dataset("C").parameter, RoughnessParameter::q1_fraction);
  EXPECT_THROW(roughness_dataset("D"), InputError);
  const nlohmann::json t = thesis_rows("A", {std::pow(10.0, -3.52), 1e-2});
  ASSERT_EQ(t.size(), 1u);  // 1 cm is not in Table D.1
  EXPECT_DOUBLE_EQ(t[0]["mu"].get<double>(), 0.4282);
  EXPECT_DOUBLE_EQ(t[0]["area"].get<double>(), 0.3180);
  EXPECT_DOUBLE_EQ(t[0]["kappa"].get<double>(), 2.16);  // Table C.1 at log h0 = -3.52
  EXPECT_DOUBLE_EQ(thesis_rows("B", {0.7})[0]["mu"].get<double>(), 0.3692);
}

// Per value: the realizations' statistics, with CoV = std / mean (the thesis's s*); a real run
// records the surface it made and fits the normal curve (>= 4 normal steps) for kappa.
TEST(RoughnessSweep, RunsAndTable) {
  RoughnessSweepSpec s = small_roughness_sweep("B", {0.7}, 2, 5);
  s.base.h0 = 2e-4;
  check_roughness_spec(s);
  std::vector<nlohmann::json> runs;
  for (int i = 0; i < roughness_run_count(s); ++i) runs.push_back(run_roughness_point(s, i, MPI_COMM_NULL, 1));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_NE(runs[0]["seed"], runs[1]["seed"]);
  EXPECT_NEAR(runs[0]["h0"].get<double>(), 2e-4, 1e-9);  // synthesis normalises h0 exactly
  ASSERT_TRUE(runs[0]["quartic"].is_object()) << runs[0].dump();
  EXPECT_EQ(runs[0]["normal_curve"]["area"].size(), 5u);
  const nlohmann::json t = roughness_table(runs);
  ASSERT_EQ(t.size(), 1u);
  const double a0 = runs[0]["contact"]["area_at_peak"].get<double>(), a1 = runs[1]["contact"]["area_at_peak"].get<double>();
  const double mean = (a0 + a1) / 2, sd = std::abs(a0 - a1) / std::sqrt(2.0);
  EXPECT_NEAR(t[0]["area_at_peak"]["mean"].get<double>(), mean, 1e-15);
  EXPECT_NEAR(t[0]["area_at_peak"]["cov"].get<double>(), sd / mean, 1e-12);
  EXPECT_EQ(t[0]["label"], "H = 0.7");
}

// A roughness sweep in the report: its own section and charts, its surfaces' (MPD, 100 mu) in the
// skid chart, every named run group in the HDF5; a coverage-only reader refuses it.
TEST(Report, RoughnessSweepSection) {
  const RoughnessSweepSpec s = small_roughness_sweep("A", {1.72e-4, 3.05e-4}, 1, 4);
  std::vector<nlohmann::json> runs;
  for (int i = 0; i < roughness_run_count(s); ++i) runs.push_back(run_roughness_point(s, i, MPI_COMM_NULL, 1));
  EXPECT_GT(runs[1]["mpd"].get<double>(), runs[0]["mpd"].get<double>());  // rougher: deeper texture
  const nlohmann::json sweep = {{"spec", roughness_spec_json(s)}, {"table", roughness_table(runs)}, {"runs", runs},
                                {"thesis", thesis_rows("A", s.values)}, {"failed_runs", 0},
                                {"provenance", {{"timings", {{"total", 1.0}, {"ranks", 1}}}}}};
  const std::string dir = ::testing::TempDir() + "wetroad-roughness-report";
  std::filesystem::create_directories(dir);
  const std::string h5 = dir + "/r.h5", html = dir + "/r.html";
  write_sweep_hdf5(h5, sweep, roughness_layout());
  EXPECT_THROW(read_sweep_hdf5(h5, coverage_layout()), InputError);
  ReportInput in;
  in.sweeps.emplace_back(h5, read_any_sweep_hdf5(h5));
  EXPECT_EQ(in.sweeps[0].second["kind"], "roughness");
  write_html_report(html, in);
  std::stringstream ss;
  ss << std::ifstream(html).rdbuf();
  const std::string doc = ss.str();
  EXPECT_NE(doc.find("Friction against roughness"), std::string::npos);
  EXPECT_NE(doc.find("thesis h0 = 0.305 mm"), std::string::npos);
  std::size_t svgs = 0;
  for (auto p = doc.find("<svg"); p != std::string::npos; p = doc.find("<svg", p + 1)) ++svgs;
  EXPECT_EQ(svgs, 4u);  // mu, area, kappa, skid numbers
  Hdf5Reader r(h5);
  for (int i = 0; i < 2; ++i) {
    char g[32];
    std::snprintf(g, sizeof g, "/runs/run-%04d", i);
    EXPECT_NE(doc.find(g), std::string::npos) << g;
    EXPECT_TRUE(r.has_group(g)) << g;
  }
  std::filesystem::remove_all(dir);
}

TEST(Report, PeakOfAQuadraticAndItsFallback) {
  const std::vector<double> x = {0.2, 0.6, 1.0, 1.4, 1.8};
  std::vector<double> y;
  for (double v : x) y.push_back(50 - 20 * (v - 1.1) * (v - 1.1));
  const PeakEstimate p = peak_position(x, y);
  EXPECT_EQ(p.method, "quadratic fit");
  EXPECT_NEAR(p.mpd_mm, 1.1, 1e-9);
  EXPECT_NEAR(p.value, 50, 1e-9);
  const PeakEstimate m = peak_position({0.2, 0.6, 1.0}, {1, 2, 3});  // rising: no interior maximum
  EXPECT_EQ(m.method, "largest value");
  EXPECT_EQ(m.mpd_mm, 1.0);
}

TEST(Report, MeasuredCsvErrorsNameTheLine) {
  const std::string path = ::testing::TempDir() + "wetroad-skid.csv";
  auto write = [&](const std::string& text) {
    std::ofstream(path) << text;
  };
  write("site,mpd_mm,sn40r,speed_kmh\nA,0.5,40,64\nB,0.9,55,\n");
  const auto ok = read_measured_skid_csv(path);
  ASSERT_EQ(ok.size(), 2u);
  EXPECT_EQ(ok[0].site, "A");
  EXPECT_DOUBLE_EQ(*ok[0].speed_kmh, 64);
  EXPECT_FALSE(ok[1].speed_kmh.has_value());
  write("site,mpd,sn40r\nA,0.5,40\n");
  EXPECT_THROW(read_measured_skid_csv(path), InputError);
  write("site,mpd_mm,sn40r\nA,0.5,40\nB,x,40\n");
  try {
    read_measured_skid_csv(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace wr
