#pragma once
// The report's part on wet friction at speed (issue 55): from the hysteresis sweeps run with a
// water film, the predicted speed constant Sp against MPD beside ASTM E1960's regression
// Sp = 14.2 + 89.7 MPD, the skid number against speed per surface (mean over realizations), and
// the comparison of the model's SN40R with the IFI route, with the cause of their difference.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

// "" when no sweep carries the film model's fields (sp_kmh, sn_against_speed).
std::string skid_speed_section(const std::vector<std::pair<std::string, nlohmann::json>>& sweeps, const std::string& chart_dir);

// ASTM E1960's speed constant from MPD (km/h; mpd in mm): PIARC's regression.
inline double piarc_speed_constant(double mpd_mm) { return 14.2 + 89.7 * mpd_mm; }

}  // namespace wr
