#include "lib/friction/dma_data.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"
#include "lib/io/input_file.hpp"

namespace wr {
namespace {

enum class Quantity { temperature, frequency, storage, loss, strain };

struct Column {
  Quantity what;
  double scale = 1, offset = 0;  // SI (or deg C) = value * scale + offset
  bool fahrenheit = false, shear = false;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\"");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\"");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

Column column_of(const std::string& header, const std::string& source) {
  const auto open = header.find('['), close = header.rfind(']');
  const std::string name = lower(trim(header.substr(0, open)));
  if (open == std::string::npos || close == std::string::npos || close < open)
    throw InputError(source, "column \"" + header + "\" has no unit: write it as name [unit], e.g. \"temperature [C]\"");
  const std::string unit = lower(trim(header.substr(open + 1, close - open - 1)));
  auto modulus_scale = [&](const std::string& u) -> double {
    if (u == "pa") return 1;
    if (u == "kpa") return 1e3;
    if (u == "mpa") return 1e6;
    if (u == "gpa") return 1e9;
    throw InputError(source, "column \"" + header + "\": unit \"" + u + "\" is not Pa, kPa, MPa or GPa");
  };
  Column c{};
  if (name == "temperature" || name == "t") {
    c.what = Quantity::temperature;
    if (unit == "c" || unit == "°c" || unit == "deg c") return c;
    if (unit == "k") return {Quantity::temperature, 1, -273.15};
    if (unit == "f" || unit == "°f" || unit == "deg f") return {Quantity::temperature, 5.0 / 9.0, -32 * 5.0 / 9.0, true};
    throw InputError(source, "column \"" + header + "\": temperature unit \"" + unit + "\" is not C, K or F");
  }
  if (name == "frequency" || name == "f") {
    if (unit == "hz") return {Quantity::frequency, 2 * M_PI, 0};
    if (unit == "rad/s") return {Quantity::frequency, 1, 0};
    throw InputError(source, "column \"" + header + "\": frequency unit \"" + unit + "\" is not Hz or rad/s");
  }
  for (const char* n : {"e'", "e_storage", "storage_modulus", "g'", "g_storage"})
    if (name == n) return {Quantity::storage, modulus_scale(unit), 0, false, name[0] == 'g'};
  for (const char* n : {"e''", "e\"", "e_loss", "loss_modulus", "g''", "g\"", "g_loss"})
    if (name == n) return {Quantity::loss, modulus_scale(unit), 0, false, name[0] == 'g'};
  if (name == "strain") {
    if (unit == "-" || unit == "1") return {Quantity::strain, 1, 0};
    if (unit == "%") return {Quantity::strain, 0.01, 0};
    throw InputError(source, "column \"" + header + "\": strain unit \"" + unit + "\" is not - or %");
  }
  throw InputError(source, "unknown column \"" + header +
                               "\" (temperature, frequency, E' and E'' or G' and G'', strain; docs/file-formats.md)");
}

double cell_number(const std::string& cell, const std::string& source, int line, const std::string& header) {
  const std::string at = source + ":" + std::to_string(line);
  if (cell.empty()) throw InputError(at, "column \"" + header + "\" is empty");
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != cell.size() || !std::isfinite(v)) throw InputError(at, "column \"" + header + "\": \"" + cell + "\" is not a finite number");
  return v;
}

}  // namespace

DmaData parse_dma_csv(const std::string& text, const std::string& source, double poisson) {
  if (!(poisson > -1 && poisson <= 0.5)) throw InputError("--poisson", "must lie in (-1, 0.5]");
  std::istringstream in(text);
  std::string line;
  int number = 0;
  std::vector<Column> cols;
  std::vector<std::string> headers;
  std::map<long, Isotherm> by_t;  // key: temperature in units of 0.05 K
  DmaData d;
  d.source = source;
  d.poisson = poisson;
  bool strain_seen = false;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const std::vector<std::string> cells = split(line);
    if (cols.empty()) {
      headers = cells;
      for (const std::string& h : cells) cols.push_back(column_of(h, source));
      for (Quantity q : {Quantity::temperature, Quantity::frequency, Quantity::storage, Quantity::loss}) {
        const auto n = std::count_if(cols.begin(), cols.end(), [q](const Column& c) { return c.what == q; });
        static const char* names[] = {"temperature", "frequency", "E' (or G')", "E'' (or G'')", "strain"};
        if (n != 1) throw InputError(source, std::string(n ? "more than one " : "no ") + names[int(q)] + " column");
      }
      const bool gs = std::find_if(cols.begin(), cols.end(), [](const Column& c) { return c.what == Quantity::storage; })->shear;
      const bool gl = std::find_if(cols.begin(), cols.end(), [](const Column& c) { return c.what == Quantity::loss; })->shear;
      if (gs != gl) throw InputError(source, "storage and loss columns must both be Young's (E) or both shear (G) moduli");
      d.shear = gs;
      continue;
    }
    if (cells.size() != cols.size())
      throw InputError(source + ":" + std::to_string(number), std::to_string(cells.size()) + " columns, the header has " +
                                                                  std::to_string(cols.size()));
    double t = 0, w = 0, e1 = 0, e2 = 0;
    for (std::size_t k = 0; k < cols.size(); ++k) {
      const double v = cell_number(cells[k], source, number, headers[k]) * cols[k].scale + cols[k].offset;
      const std::string at = source + ":" + std::to_string(number);
      switch (cols[k].what) {
        case Quantity::temperature:
          if (!(v > -273.15)) throw InputError(at, "temperature below absolute zero");
          t = v;
          break;
        case Quantity::frequency:
          if (!(v > 0)) throw InputError(at, "frequency must be > 0");
          w = v;
          break;
        case Quantity::storage:
          if (!(v > 0)) throw InputError(at, "column \"" + headers[k] + "\": a storage modulus must be > 0");
          e1 = v * (d.shear ? 2 * (1 + poisson) : 1);
          break;
        case Quantity::loss:
          if (!(v > 0)) throw InputError(at, "column \"" + headers[k] + "\": a loss modulus must be > 0");
          e2 = v * (d.shear ? 2 * (1 + poisson) : 1);
          break;
        case Quantity::strain:
          if (!(v > 0)) throw InputError(at, "strain amplitude must be > 0");
          d.strain_min = strain_seen ? std::min(d.strain_min, v) : v;
          d.strain_max = strain_seen ? std::max(d.strain_max, v) : v;
          strain_seen = true;
          break;
      }
    }
    Isotherm& iso = by_t[std::lround(t / 0.05)];
    iso.temperature = t;
    iso.omega.push_back(w);
    iso.storage.push_back(e1);
    iso.loss.push_back(e2);
    iso.rows.push_back(number);
    ++d.points;
  }
  if (cols.empty()) throw InputError(source, "empty: no header line");
  for (auto& [key, iso] : by_t) {
    std::vector<std::size_t> order(iso.omega.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return iso.omega[a] < iso.omega[b]; });
    Isotherm s;
    s.temperature = iso.temperature;
    for (std::size_t i : order) {
      s.omega.push_back(iso.omega[i]);
      s.storage.push_back(iso.storage[i]);
      s.loss.push_back(iso.loss[i]);
      s.rows.push_back(iso.rows[i]);
    }
    const std::string at = source + ": isotherm " + number_text(s.temperature) + " C";
    if (s.omega.size() < 3) throw InputError(at, "has " + std::to_string(s.omega.size()) + " frequencies; at least 3 are needed");
    for (std::size_t i = 1; i < s.omega.size(); ++i) {
      if (s.omega[i] <= s.omega[i - 1] * (1 + 1e-9))
        throw InputError(source + ":" + std::to_string(s.rows[i]), "frequency given twice in the isotherm at " + number_text(s.temperature) + " C");
      // E' of a relaxing solid rises with frequency; a fall beyond 5 % (noise) is not a material
      if (s.storage[i] < 0.95 * s.storage[i - 1])
        throw InputError(source + ":" + std::to_string(s.rows[i]),
                         "E' falls with frequency in the isotherm at " + number_text(s.temperature) + " C (" +
                             number_text(s.storage[i - 1]) + " -> " + number_text(s.storage[i]) + " Pa): not a relaxing solid");
    }
    d.isotherms.push_back(std::move(s));
  }
  if (d.isotherms.size() < 2) throw InputError(source, "needs frequency sweeps at 2 or more temperatures for a master curve");
  return d;
}

DmaData read_dma_csv(const std::string& path, double poisson) {
  return parse_dma_csv(read_input_file(path, "DMA file"), path, poisson);
}

}  // namespace wr
