#pragma once
// What `wetroad contact` prints and records per run (app layer: formatting only).
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/contact/contact_step.hpp"
#include "lib/core/height_map.hpp"

namespace wr::app {

// The area-load fits over the converged normal steps: the low-pressure kappa (sec. 5.2.3), the
// quartic (eq. 5.4) and YAM (eq. 3.179) from four or more; null without a converged normal step.
// `talk`: print them. `central_ratio` > 0 adds kappa with sigma* over the central-difference slope.
nlohmann::json area_load_fit_json(const std::vector<ContactStep>& steps, bool talk, double central_ratio = 0);

// Adds "peak", "rms_slope_central" and "area_load_fit" to `j` (which holds "rms_slope" of
// `obstacle`); returns the peak step (nullptr without one).
const ContactStep* add_curve_summaries(nlohmann::json& j, const std::vector<ContactStep>& steps, bool talk,
                                       const HeightMap& obstacle);

void print_peak(const ContactStep* peak, const std::vector<ContactStep>& steps);
void print_step_header();
void print_step_row(int k, const ContactStep& st);

}  // namespace wr::app
