#pragma once
// The files of a coverage sweep (lib/sweep/coverage_sweep.hpp), written atomically:
//  - HDF5: /sweep (the whole result as JSON text: spec, table, runs, provenance), /table/<column>
//    (one value per target coverage: target, coverage, mu_peak, mu_ratio, area_at_peak,
//    area_normal, mean_pool_depth, wet_sq, with _std and _ci95 beside the means) and per run
//    /runs/run-NNNN/psd_q, psd_C and the step curves (ux, mu, fz, area_fraction), with the
//    run's record as attribute "record";
//  - CSV: the table, one row per target coverage;
//  - SVG charts (gnuplot): mu_wet/mu_dry and A/A0 against coverage (Figure 5.25), the wet
//    PSDs (Figure 5.26), the mean pool depth against coverage.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

// `sweep`: {"spec", "table", "runs", "provenance"}.
void write_coverage_hdf5(const std::string& path, const nlohmann::json& sweep);
void write_coverage_csv(const std::string& path, const nlohmann::json& table);
// Returns the chart files written into `dir` (created if missing): mu_ratio.svg, area.svg,
// wet_psd.svg, pool_depth.svg.
std::vector<std::string> write_coverage_plots(const std::string& dir, const nlohmann::json& sweep);

// Reads back the JSON of write_coverage_hdf5 (InputError when the file is not a sweep).
nlohmann::json read_coverage_hdf5(const std::string& path);

}  // namespace wr
