#include "reports/plot.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "lib/core/utf8.hpp"
#include "lib/io/atomic_output.hpp"

namespace wr {
namespace {

// gnuplot string literal: single quotes, embedded quotes doubled.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// `s` as one word for /bin/sh: inside single quotes nothing is special but the quote itself,
// written '\'' (a file name with a quote must neither break the command nor name another file).
std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A title or label as a gnuplot literal. A line break would end the command (and let a file name
// in a label write gnuplot commands), and the SVG is inlined into a UTF-8 page: controls become
// blanks and bytes that are not UTF-8 U+FFFD (gnuplot escapes & < > itself). gnuplot 5.4 ends a
// single-quoted label at a doubled quote (measured: a ylabel E'' written with the quotes doubled is
// a syntax error), so an apostrophe is written as U+2019, which reads the same.
std::string quoted_text(const std::string& s) {
  std::string t = "'";
  for (std::size_t i = 0; i < s.size();) {
    char32_t cp = 0;
    const std::size_t n = utf8_length_at(s, i, &cp);
    if (n == 0) t += "\xEF\xBF\xBD";
    else if (cp == '\'') t += "\xE2\x80\x99";
    else if (is_control(cp)) t += ' ';
    else t.append(s, i, n);
    i += n == 0 ? 1 : n;
  }
  return t + "'";
}

}  // namespace

void write_svg_plot(const std::string& path, const PlotSpec& spec) {
  std::ostringstream g;
  g.precision(17);
  const std::string tmp = temporary_sibling(path, ".svg");
  g << "set terminal svg size 800,560 dynamic enhanced font 'sans,12' background rgb 'white'\n";
  g << "set output " << quoted(tmp) << "\n";
  g << "set title " << quoted_text(spec.title) << " noenhanced\n";
  g << "set xlabel " << quoted_text(spec.xlabel) << " noenhanced\nset ylabel " << quoted_text(spec.ylabel) << " noenhanced\n";
  const bool known_key = spec.key == "top left" || spec.key == "top right" || spec.key == "bottom left" ||
                         spec.key == "bottom right" || spec.key == "outside right";
  g << "set grid\nset key " << (known_key ? spec.key : std::string("top left")) << " noenhanced opaque box\n";
  if (spec.logx) g << "set logscale x\nset format x '10^{%L}'\n";
  if (spec.logy) g << "set logscale y\nset format y '10^{%L}'\n";
  // Series without a finite point are left out (gnuplot refuses empty data); a chart with no
  // point at all says so instead of failing.
  std::vector<std::size_t> drawn;
  for (std::size_t s = 0; s < spec.series.size(); ++s) {
    const PlotSeries& ps = spec.series[s];
    if (ps.x.size() != ps.y.size() || (!ps.yerr.empty() && ps.yerr.size() != ps.y.size()))
      throw std::runtime_error(path + ": series '" + ps.label + "' has x, y (and yerr) of different lengths");
    std::ostringstream d;
    d.precision(17);
    std::size_t points = 0;
    for (std::size_t k = 0; k < ps.x.size(); ++k)
      if (std::isfinite(ps.x[k]) && std::isfinite(ps.y[k]) && (!spec.logx || ps.x[k] > 0) && (!spec.logy || ps.y[k] > 0)) {
        d << ps.x[k] << " " << ps.y[k];
        if (!ps.yerr.empty()) d << " " << (std::isfinite(ps.yerr[k]) ? ps.yerr[k] : 0.0);
        d << "\n";
        ++points;
      }
    if (points == 0) continue;
    g << "$d" << s << " << EOD\n" << d.str() << "EOD\n";
    drawn.push_back(s);
  }
  if (drawn.empty()) {
    g << "unset logscale\nset xrange [0:1]\nset yrange [0:1]\nset label 1 'no data to draw' at graph 0.5,0.5 center\n"
      << "plot 2 notitle";
  } else {
    g << "plot ";
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      const PlotSeries& ps = spec.series[drawn[i]];
      g << (i ? ", " : "") << "$d" << drawn[i]
        << (ps.yerr.empty() ? " using 1:2 with " + ps.style : std::string(" using 1:2:3 with yerrorlines"))
        << " lw 2 title " << quoted_text(ps.label);
    }
  }
  g << "\nunset output\n";
  const std::string script = temporary_sibling(path, ".gp");
  {
    std::ofstream f(script);
    f << g.str();
    if (!f) throw std::runtime_error(path + ": cannot write the gnuplot script " + script);
  }
  const std::string cmd = "gnuplot " + shell_quoted(script) + " 2>&1";
  std::string output;
  int status = -1;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[512];
    while (std::fgets(buf, sizeof buf, p)) output += buf;
    status = pclose(p);
  }
  std::filesystem::remove(script);
  if (status != 0 || !std::filesystem::exists(tmp)) {
    std::filesystem::remove(tmp);
    throw std::runtime_error(path + ": gnuplot failed (is Debian's gnuplot-nox installed?): " +
                             output.substr(0, output.find('\n')));
  }
  commit_file(tmp, path);
}

}  // namespace wr
