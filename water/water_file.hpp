#pragma once
// Output of `wetroad fill` (HDF5): /height = wet surface max(h, level) (itself a valid surface
// for analyze and contact), /water_depth = level - h (0 where dry), /ground = the input, with
// dx, dy, unit, periodic, the summary as root attributes and the provenance (JSON).
#include <string>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"
#include "water/fill_spill_merge.hpp"

namespace wr {

void write_water_file(const std::string& path, const HeightMap& ground, const WaterState& w,
                      const nlohmann::json& summary, const nlohmann::json& provenance);

}  // namespace wr
