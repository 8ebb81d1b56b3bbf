#pragma once
// Output of `wetroad fill` (HDF5): /height = wet surface max(h, level) (itself a valid surface
// for analyze and contact), /water_depth = level - h (0 where dry), /ground = the input, with
// dx, dy, unit, periodic, the summary as root attributes and the provenance (JSON).
#include <string>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"
#include "water/fill_spill_merge.hpp"

namespace wr {

// `dry_sha256`: the SHA-256 of the dry surface file fill read (root attribute dry_surface_sha256),
// which ties the wet file to that surface (check_wet_file).
void write_water_file(const std::string& path, const HeightMap& ground, const WaterState& w,
                      const nlohmann::json& summary, const nlohmann::json& provenance);

// What a command reading `--wet W` beside its dry surface `--surface S` may rely on: W is the
// HDF5 output of `wetroad fill` (/height, /water_depth, /ground of one shape), made from S itself
// (the SHA-256 of S's bytes equals W's dry_surface_sha256), with finite water depths >= 0.
// Returns the water coverage (the fraction of cells with depth > 0). InputError naming W otherwise:
// an X3P (the wet surface only), a dry surface, another surface, another size, a file written
// before wet files recorded their surface, negative or non-finite depths.
double check_wet_file(const std::string& wet_path, const std::string& dry_path);

}  // namespace wr
