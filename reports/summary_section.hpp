#pragma once
// The report's first table: one row per surface with the answers an engineer reads first (MPD,
// the predicted SN40R with its band, Sp, FR60 and F60 where available, the validity flags that
// failed), and the measured sites beside them. A dry road has no skid number; the FEM's
// elastostatic mu is not one either (those sweeps are listed by name below the table).
#include <string>

#include "reports/html_report.hpp"

namespace wr {

std::string summary_section_html(const ReportInput& in);

}  // namespace wr
