#pragma once
// Height-map files (design.md "Files"): HDF5 with /height (2-D, rows = y) or /profile (1-D),
// attributes dx, dy [m], unit, periodic; a /synthesis group when `synth` made the file, holding
// the prescribed spectrum; root attribute `provenance` (JSON).
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"
#include "roads/self_affine_psd.hpp"
#include "roads/synthesize.hpp"

namespace wr {

struct SynthesisRecord {
  SelfAffinePsd psd;                // prescribed spectrum (lattice-normalised k)
  double k_eq44 = 0;                // m^4
  double h0_eq44_on_lattice = 0;    // m
  std::uint64_t seed = 0;
  int oversample = 1;
  Sampling sampling = Sampling::nyquist;
};

// Writes `map` (and the synthesis record, if any) atomically to `path`.
void write_surface_file(const std::string& path, const HeightMap& map,
                        const std::optional<SynthesisRecord>& synthesis, const nlohmann::json& provenance);

}  // namespace wr
