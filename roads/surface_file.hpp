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

// The container of a written surface: wetroad's HDF5, or X3P (ISO 25178-72, roads/x3p_file.hpp)
// for other tools (Gwyddion, MountainsMap, openGPS).
enum class SurfaceFormat { hdf5, x3p };

// From a --format value: "hdf5", "x3p", or "auto" (x3p when `path` ends in .x3p, any case;
// hdf5 otherwise). InputError("--format", ...) for anything else.
SurfaceFormat output_format(const std::string& path, const std::string& format);

// Writes `map` (and the synthesis record, if any) atomically to `path`. X3P keeps heights,
// spacings and periodicity; the synthesis record goes into its provenance (wetroad.json).
void write_surface_file(const std::string& path, const HeightMap& map,
                        const std::optional<SynthesisRecord>& synthesis, const nlohmann::json& provenance,
                        SurfaceFormat format = SurfaceFormat::hdf5);

}  // namespace wr
