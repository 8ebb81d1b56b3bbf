#pragma once
// Dynamic-mechanical (DMA) measurements of a rubber: frequency sweeps at a series of
// temperatures, as a lab hands them over, read from CSV into isotherms of Young's moduli.
//
// File: one header line of named columns with their units in brackets, then one row per point;
// '#' starts a comment line; blank lines are skipped. Columns (names case-insensitive, any order):
//   temperature [C | K | F]            ("temperature" or "T"; F only when written so)
//   frequency   [Hz | rad/s]           ("frequency" or "f")
//   E' [Pa|kPa|MPa|GPa] and E'' [...]  (also "E_storage", "E_loss"), or the shear moduli G' and
//                                      G'' ("G_storage", "G_loss"), turned into Young's by
//                                      E = 2 (1 + nu) G (nu = 0.5: the 3x rule)
//   strain      [- | %]                (optional: the strain amplitude, recorded)
// Every column needs its unit: a temperature without one could be Celsius or Fahrenheit.
// Example:  temperature [C],frequency [Hz],E' [MPa],E'' [MPa]
//           -20,0.1,120.5,35.2
#include <string>
#include <vector>

namespace wr {

struct Isotherm {
  double temperature = 0;           // deg C
  std::vector<double> omega;        // rad/s, ascending
  std::vector<double> storage, loss;  // E', E'' in Pa (Young's)
  std::vector<int> rows;            // the file's line of each point (for messages)
};

struct DmaData {
  std::string source;
  std::vector<Isotherm> isotherms;  // ascending in temperature
  bool shear = false;               // the file gave G', G'' (converted with `poisson`)
  double poisson = 0.5;
  double strain_min = 0, strain_max = 0;  // the strain amplitudes given (0, 0: none)
  std::size_t points = 0;
};

// Reads and checks `path` (InputError naming the file and the line or column): a missing or
// unknown unit, a missing column, a non-number, a non-positive or non-finite modulus or
// frequency, a temperature below absolute zero, an isotherm with fewer than 3 frequencies or a
// frequency given twice, E' falling with frequency within an isotherm (a non-physical sweep),
// fewer than 2 isotherms. Points of one temperature (to 0.05 K) form one isotherm.
DmaData read_dma_csv(const std::string& path, double poisson = 0.5);
DmaData parse_dma_csv(const std::string& text, const std::string& source, double poisson = 0.5);

}  // namespace wr
