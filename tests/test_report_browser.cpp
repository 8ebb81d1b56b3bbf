// The report in a real browser (issue 56, bar 5): headless Chromium (Debian's
// chromium-headless-shell, installed by scripts/install-deps.sh) loads the demo-like report,
// lays it out and screenshots it without a console message or a failed load, and its DOM holds
// the summary first and every chart inline.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "tests/cli_fixture.hpp"

namespace {

using wr_test::Cli;
using wr_test::CliRun;
namespace fs = std::filesystem;

class ReportBrowser : public Cli {};

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST_F(ReportBrowser, OpensInHeadlessChromiumWithoutErrors) {
  const std::string browser = "/usr/bin/chromium-headless-shell";
  ASSERT_TRUE(fs::exists(browser)) << "Debian's chromium-headless-shell is missing: run scripts/install-deps.sh";
  ASSERT_EQ(run("synth --size 64 --dx 2e-4 --h0 1e-4 --seed 3 -q -o " + path("s.h5")).code, 0);
  const CliRun f = run("friction " + path("s.h5") + " --band --speeds 1 17.9 --out " + path("f.h5") + " -q");
  ASSERT_EQ(f.code, 0) << f.err;
  const CliRun r = run("report --friction " + path("f.h5") + " -o " + path("r.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string common = browser + " --no-sandbox --disable-gpu --log-level=0 --enable-logging=stderr --v=0 ";
  const std::string url = "file://" + path("r.html");
  const std::string dom = path("dom.html"), log = path("browser.log");
  ASSERT_EQ(std::system((common + "--dump-dom " + url + " >" + dom + " 2>" + log).c_str()), 0);
  ASSERT_EQ(std::system((common + "--window-size=1200,1600 --screenshot=" + path("shot.png") + " " + url + " >>" + log + " 2>&1").c_str()), 0);
  const std::string page = slurp(dom), messages = slurp(log);
  // the summary is the first section; every figure is an inline SVG (nothing to load)
  const auto summary = page.find("<h2>Summary</h2>");
  ASSERT_NE(summary, std::string::npos);
  EXPECT_EQ(summary, page.find("<h2>"));
  EXPECT_GE(count(page, "<svg"), 3u);
  EXPECT_EQ(count(page, "<img"), 0u);
  // no console message, no failed load (Chromium's own D-Bus complaints on a machine without a
  // session bus are not the page's)
  for (const char* bad : {"CONSOLE", "Failed to load resource", "net::ERR", "Uncaught"})
    EXPECT_EQ(messages.find(bad), std::string::npos) << bad << " in\n" << messages;
  EXPECT_GT(fs::file_size(path("shot.png")), 10000u);  // a rendered page, not a blank
}

}  // namespace
