#pragma once
// The files of a sweep (lib/sweep/coverage_sweep.hpp, roughness_sweep.hpp), written atomically:
//  - HDF5: /sweep (the whole result as JSON text: spec, table, runs, provenance), root
//    attribute kind ("wetroad coverage sweep" / "wetroad roughness sweep"), /table/<column>
//    (one value per table row: the row's x column, then each statistic column's mean with
//    _std and _ci95 beside it) and per run /runs/run-NNNN with the run's record as attribute
//    "record", its PSD (psd_q, psd_C) when it has one and its step curves (steps_ux, _uz, _mu,
//    _fz, _fx, _area_fraction);
//  - CSV: the table, one row per table row;
//  - SVG charts (gnuplot): coverage sweeps: mu_wet/mu_dry and A/A0 against coverage
//    (Figure 5.25), the wet PSDs (Figure 5.26), the mean pool depth; roughness sweeps: mu, A/A0
//    and kappa against the swept parameter next to the thesis's Tables D and C.1.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

// Which sweep, and the columns of its table rows: `x` a number per row, `stats` objects
// {mean, std, ci95, n}.
struct SweepTableLayout {
  std::string kind;  // HDF5 root attribute
  std::string x;
  std::vector<std::string> stats;
};
const SweepTableLayout& coverage_layout();
const SweepTableLayout& roughness_layout();

// `sweep`: {"spec", "table", "runs", "provenance"}.
void write_sweep_hdf5(const std::string& path, const nlohmann::json& sweep, const SweepTableLayout& layout);
// Reads back the JSON of write_sweep_hdf5 (InputError when the file is not that kind of sweep).
nlohmann::json read_sweep_hdf5(const std::string& path, const SweepTableLayout& layout);
// Either kind: the JSON with "kind" set to "coverage" or "roughness" (InputError otherwise).
nlohmann::json read_any_sweep_hdf5(const std::string& path);
void write_sweep_csv(const std::string& path, const nlohmann::json& table, const SweepTableLayout& layout);
// Returns the chart files written into `dir` (created if missing): mu_ratio.svg, area.svg,
// wet_psd.svg, pool_depth.svg.
std::vector<std::string> write_coverage_plots(const std::string& dir, const nlohmann::json& sweep);
// Roughness sweeps: mu.svg, area.svg, kappa.svg against the swept parameter, each with the
// thesis's values (sweep["thesis"]) beside the sweep's means and 95 % CIs.
std::vector<std::string> write_roughness_plots(const std::string& dir, const nlohmann::json& sweep);

}  // namespace wr
