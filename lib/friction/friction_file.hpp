#pragma once
// `wetroad friction --out F.h5`: the mu(v) curves as HDF5 (written atomically).
//   /speeds (m/s), /dry/{mu, area_fraction, temperature_rise, mu_extrapolated},
//   /wet_homogeneous/..., /wet_local/... (with --wet), /spectrum/{q, C} (the spectrum the rubber
//   feels: measured nodes, then the extension), the dataset /summary (the JSON of
//   friction_run_json) and the root attribute "provenance" (JSON).
#include <string>

#include <nlohmann/json.hpp>

#include "lib/friction/friction_scene.hpp"

namespace wr {

void write_friction_file(const std::string& path, const FrictionRun& r, const nlohmann::json& summary,
                         const nlohmann::json& provenance);

}  // namespace wr

namespace wr {

// The /summary JSON of a file written by write_friction_file (InputError naming the file when it
// is not one).
nlohmann::json read_friction_summary(const std::string& path);

}  // namespace wr
