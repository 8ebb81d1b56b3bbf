#pragma once
// Charts as SVG files, drawn by gnuplot (Debian's gnuplot-nox; scripts/install-deps.sh installs
// it): the data go inline into a gnuplot script, gnuplot renders to a temporary file next to
// the target, which is renamed into place only when gnuplot succeeded.
#include <string>
#include <vector>

namespace wr {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::string style = "linespoints";  // gnuplot style: lines, points, linespoints
  std::vector<double> yerr;  // optional half-widths: drawn as error bars (yerrorlines, style ignored)
};

struct PlotSpec {
  std::string title, xlabel, ylabel;
  bool logx = false, logy = false;
  std::vector<PlotSeries> series;
  std::string key = "top left";  // where the legend goes (gnuplot's "set key" position)
};

// Throws std::runtime_error naming the file when gnuplot is missing or fails, or a series has
// x and y of different lengths.
void write_svg_plot(const std::string& path, const PlotSpec& spec);

}  // namespace wr
