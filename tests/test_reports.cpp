// Charts: a gnuplot-rendered SVG with the data in it, written whole or not at all.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "reports/plot.hpp"

namespace wr {
namespace {

namespace fs = std::filesystem;

TEST(Plot, WritesAnSvgWithTitleAxesAndSeries) {
  const fs::path dir = fs::temp_directory_path() / ("wetroad_plot_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "chart.svg").string();
  PlotSpec p;
  p.title = "A/A0 against sigma*";
  p.xlabel = "sigma*";
  p.ylabel = "A/A0";
  p.logx = true;
  p.series.push_back({"grid 256", {0.01, 0.1, 1.0}, {0.02, 0.2, 0.9}, "linespoints", {}});
  p.series.push_back({"Persson's kappa", {0.01, 1.0}, {0.016, 1.6}, "lines", {}});
  write_svg_plot(out, p);
  std::ifstream f(out);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string svg = ss.str();
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("A/A0 against sigma*"), std::string::npos);
  EXPECT_NE(svg.find("grid 256"), std::string::npos);
  EXPECT_NE(svg.find("Persson"), std::string::npos);  // the quote in the label survived
  EXPECT_NE(svg.find("<path"), std::string::npos);    // something was drawn
  // Bad input: nothing written, the reason named.
  const std::string bad = (dir / "bad.svg").string();
  p.series.push_back({"broken", {1, 2}, {1}, "lines", {}});
  EXPECT_THROW(write_svg_plot(bad, p), std::runtime_error);
  EXPECT_FALSE(fs::exists(bad));
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);  // no temporary left behind
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wr
