// Charts: a gnuplot-rendered SVG with the data in it, written whole or not at all.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "lib/core/errors.hpp"
#include "reports/html_parts.hpp"
#include "reports/measured_csv.hpp"
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

// Issue 54, class 13: the measured skid-number CSV as spreadsheets write it (RFC 4180), and
// site names that reach the HTML only as UTF-8 text.
std::string csv_refusal(const std::string& text) {
  try {
    parse_measured_skid_csv(text, "m.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read without an error)";
}

TEST(MeasuredCsv, ReadsQuotedFieldsByteOrderMarkAndEveryLineEnd) {
  // Excel's "CSV UTF-8": a BOM, CRLF, a comma and doubled quotes inside quoted site names. Each
  // of these was refused before (the BOM broke the header; the comma made a fifth field).
  const auto m = parse_measured_skid_csv("\xEF\xBB\xBFsite,mpd_mm,sn40r,speed_kmh\r\n\"M4, lane 1\",0.95,61,64\r\n"
                                         "\"the \"\"old\"\" road\",1.2,55,\r\n  \"B 12\" , \"0.4\" ,40,50\r\n",
                                         "m.csv");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].site, "M4, lane 1");
  EXPECT_EQ(m[0].mpd_mm, 0.95);
  EXPECT_EQ(*m[0].speed_kmh, 64);
  EXPECT_EQ(m[1].site, "the \"old\" road");
  EXPECT_FALSE(m[1].speed_kmh.has_value());
  EXPECT_EQ(m[2].site, "B 12");  // blanks around a quoted field are not part of it
  EXPECT_EQ(m[2].mpd_mm, 0.4);
  // A quoted header, CR-only line ends, a blank line, a UTF-8 site name.
  const auto c = parse_measured_skid_csv("\"site\",\"mpd_mm\",\"sn40r\"\r\"Stra\xC3\x9F" "e\",0.8,52\r\rC,0.1,45", "m.csv");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].site, "Stra\xC3\x9F" "e");
  EXPECT_EQ(c[1].sn40r, 45);
}

TEST(MeasuredCsv, MalformedRecordsAreRefusedWithLineAndColumn) {
  const std::string head = "site,mpd_mm,sn40r\n";
  // An unquoted comma: the fifth field is named where it starts, with the cure.
  std::string e = csv_refusal(head + "A,0.5,40\nM4, lane 1,0.9,60\n");
  EXPECT_NE(e.find("m.csv: line 3, column 16: field 4; the header has 3"), std::string::npos) << e;
  EXPECT_NE(e.find("in quotes"), std::string::npos) << e;
  e = csv_refusal(head + "\"A,0.5,40\nB,0.6,41\n");
  EXPECT_NE(e.find("line 2, column 1: this quoted field is never closed"), std::string::npos) << e;
  e = csv_refusal(head + "\"A\"x,0.5,40\n");
  EXPECT_NE(e.find("line 2, column 4: text after a field's closing quote"), std::string::npos) << e;
  e = csv_refusal(head + "A \"x\",0.5,40\n");
  EXPECT_NE(e.find("line 2, column 3: a quote inside an unquoted field"), std::string::npos) << e;
  e = csv_refusal(head + "A,0.5\n");
  EXPECT_NE(e.find("line 2, column 3: the record ends after 2 fields"), std::string::npos) << e;
  e = csv_refusal("site,mpd,sn40r\nA,0.5,40\n");
  EXPECT_NE(e.find("line 1, column 6: the header must be"), std::string::npos) << e;
  // A line break inside a quoted field is read as part of it (RFC 4180), and then refused in a
  // site name (the next test); one in an unclosed field is counted: the opening quote is named.
  e = csv_refusal(head + "A,0.5,40\r\nB,\"0.5\r\n,41\r\nC,0.5,40\r\n");
  EXPECT_NE(e.find("line 3, column 3: this quoted field is never closed"), std::string::npos) << e;
  e = csv_refusal(head + "A,\"0.5\r\n\",41\r\n");
  EXPECT_NE(e.find("line 2, column 3 (mpd_mm): '0.5\\x0d\\x0a' is not a number"), std::string::npos) << e;
  // A NUL inside a number is not the digits before it.
  e = csv_refusal(head + std::string("A,0.9\0" "5,40\n", 11));
  EXPECT_NE(e.find("line 2, column 3 (mpd_mm): '0.9\\x005'"), std::string::npos) << e;
}

TEST(MeasuredCsv, SiteNamesMustBeUtf8TextNamedByLineAndColumn) {
  const std::string head = "site,mpd_mm,sn40r\n";
  // Latin-1 "Straße": refused (not replaced) so that the user re-saves the file as UTF-8.
  std::string e = csv_refusal(head + "A,0.5,40\nStra\xDF" "e,0.8,52\n");
  EXPECT_NE(e.find("line 3, column 5 (site): byte 0xDF is not UTF-8"), std::string::npos) << e;
  e = csv_refusal(head + "\"\xC3\xA9t\xE9\",0.8,52\n");  // the column counts characters, not bytes
  EXPECT_NE(e.find("line 2, column 4 (site): byte 0xE9"), std::string::npos) << e;
  e = csv_refusal(head + "\xC0\xAF" ",0.8,52\n");  // an overlong '/'
  EXPECT_NE(e.find("line 2, column 1 (site): byte 0xC0"), std::string::npos) << e;
  e = csv_refusal(head + std::string("A\0B,0.8,52\n", 11));
  EXPECT_NE(e.find("line 2, column 2 (site): a control character (U+0000)"), std::string::npos) << e;
  e = csv_refusal(head + "\"two\nlines\",0.8,52\n");
  EXPECT_NE(e.find("line 2, column 5 (site): a control character (U+000A)"), std::string::npos) << e;
}

TEST(Html, EscapeLeavesNoMarkupNoControlAndOnlyUtf8) {
  EXPECT_EQ(html::escape("<b a=\"1\" c='2'>&</b>"), "&lt;b a=&quot;1&quot; c=&#39;2&#39;&gt;&amp;&lt;/b&gt;");
  EXPECT_EQ(html::escape(std::string("a\0b\x01\x7f" "c", 6)), "a&#xFFFD;b&#xFFFD;&#xFFFD;c");
  EXPECT_EQ(html::escape("Stra\xDF" "e \xC3\xA9 \xE2\x82\xAC\t\n"), "Stra&#xFFFD;e \xC3\xA9 \xE2\x82\xAC\t\n");
  EXPECT_EQ(html::escape("\xC2\x85" "x\xED\xA0\x80"), "&#xFFFD;x&#xFFFD;&#xFFFD;&#xFFFD;");  // C1 NEL; a surrogate
}

}  // namespace
}  // namespace wr

#include "reports/html_report.hpp"

namespace wr {
namespace {

// Issue 56: the summary is the first thing after the title; a friction result without a film
// shows no skid number; an apostrophe in a chart label reaches gnuplot whole (it used to end
// gnuplot's quoted string).
TEST(Html, SummaryComesFirstAndADryRoadHasNoSkidNumber) {
  const std::string dir = ::testing::TempDir() + "wetroad-summary-" + std::to_string(::getpid());
  fs::create_directories(dir);
  ReportInput in;
  nlohmann::json dry = {{"compound", {{"name", "c"}, {"synthetic", true}}}, {"flash_temperature", false},
                        {"pressure", 3e5}, {"temperature", 20}, {"q0", 200}, {"q1", 3e5}, {"q_measured", 3e4}, {"mpd", 4.5e-4},
                        {"speeds", {{{"v", 1.0}, {"mu", 0.5}, {"area_fraction", 0.01}, {"temperature_rise", 0.0}}}},
                        {"peak", {{"mu", 0.5}, {"v", 1.0}}}, {"locked_wheel", {{"mu", 0.5}, {"temperature_rise", 0.0}}},
                        {"sn64", 50.0}, {"validity", {{"checks", nlohmann::json::array()}}}};
  in.friction.push_back({"dry.h5", dry});
  in.measured.push_back({"site A", 0.8, 55, std::nullopt});
  write_html_report(dir + "/r.html", in);
  std::ifstream f(dir + "/r.html");
  const std::string html((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto h1 = html.find("<h1>"), summary = html.find("<h2>Summary</h2>"), first_h2 = html.find("<h2>");
  ASSERT_NE(summary, std::string::npos);
  EXPECT_EQ(summary, first_h2);
  EXPECT_LT(h1, summary);
  EXPECT_NE(html.find("no film: no skid number"), std::string::npos);
  EXPECT_NE(html.find("site A"), std::string::npos);
  EXPECT_EQ(html.find("(SN 50"), std::string::npos);  // the dry curve is no longer called a skid number
  PlotSpec p{"Persson's theory", "E' [Pa]", "E'' [Pa]", false, false, {{"it's", {1, 2}, {1, 2}, "lines", {}}}};
  EXPECT_NO_THROW(write_svg_plot(dir + "/q.svg", p));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wr
