#pragma once
// `wetroad report`: one self-contained HTML file (inline CSS and SVG charts drawn by gnuplot,
// no external reference, readable offline) from coverage and roughness sweeps
// (reports/sweep_outputs.hpp, read_any_sweep_hdf5) and, optionally, measured skid numbers.
//
// Sections: the hysteresis friction mu(v) of every friction result (reports/friction_section);
// the scene and model of every sweep with the validity flags of every run; for a
// coverage sweep friction and contact area against water coverage (Figure 5.25), the wet PSDs
// (Figure 5.26) and the pool depth; for a roughness sweep mu, A/A0 and kappa against the swept
// parameter beside the thesis's Tables D and C.1; each with its table; the skid-number
// comparison: predicted SN40R = 100 mu against MPD
// next to the measured (MPD, SN40R) pairs, the MPD of the friction peak of each (quadratic fit,
// or the largest value when the fit has no maximum), and the IFI speed constant
// Sp = 14.2 + 89.7 MPD [km/h, MPD in mm] (ASTM E1960) per measured site; with device constants
// A, B (and C times Tx), F60 = A + B FR(S) exp((S - 60) / Sp) + C Tx, FR = SN / 100.
// Every number carries its source: the sweep file and the run group (/runs/run-NNNN) in it.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/measured_csv.hpp"

namespace wr {

struct IfiConstants {
  double a = 0, b = 0, c = 0;  // device calibration constants (user parameters)
  double texture_tx = 0;       // Tx for the C term (mm)
};

struct ReportInput {
  std::vector<std::pair<std::string, nlohmann::json>> sweeps;  // file, read_sweep_hdf5(, coverage_layout())
  std::vector<std::pair<std::string, nlohmann::json>> friction;  // file, its summary (wetroad friction --out)
  std::vector<MeasuredSkid> measured;
  std::string measured_path;
  std::optional<IfiConstants> ifi;
  std::string title = "wetroad report: wet friction";
};

struct PeakEstimate {
  double mpd_mm = 0, value = 0;
  std::string method;  // "quadratic fit" or "largest value"
};
// The MPD at which y(mpd) peaks: the vertex of a least-squares quadratic when it opens downward
// and lies within the data's range, else the largest point. Needs >= 1 point.
PeakEstimate peak_position(const std::vector<double>& mpd_mm, const std::vector<double>& y);

// Writes the HTML atomically; charts are rendered through a temporary directory next to it.
void write_html_report(const std::string& path, const ReportInput& in);

}  // namespace wr
