#pragma once
// X3P files (ISO 25178-72, the XML format of ISO 5436-2): what confocal microscopes, laser
// scanners and tools such as Gwyddion, MountainsMap and openGPS exchange. A zip archive holding
// main.xml (axes, sizes, data type, checksums), bindata/data.bin (little-endian, x fastest),
// optionally bindata/valid.bin (one bit per point, least significant bit first, 1 = valid) and
// md5checksum.hex ("<md5 of main.xml> *main.xml").
//
// Read: feature types SUR (areal map) and PRF (profile, SizeY = 1); CX and CY incremental
// (AxisType I, Increment = spacing in m, > 0), CZ absolute; one layer (SizeZ = 1); data types
// I (int16), L (int32), F (float32), D (float64) in bindata or inline (DataList); heights
// z = Offset + Increment x raw in metres (the openGPS samples' convention; Increment defaults
// to 1 and Offset to 0). Invalid points: NaN, or a 0 bit of valid.bin; they come back as NaN.
// Both MD5 checksums (main.xml, data, valid points) are verified where given.
// Refused with InputError naming the file: not a zip or a damaged one (bad CRC), no main.xml,
// main.xml not XML or not ISO5436_2, a checksum mismatch, feature type PCL, absolute x/y axes,
// several layers, a data file of the wrong size, an unknown data type.
//
// Write: SUR or PRF (from the HeightMap's kind), data type D with Increment 1 and Offset 0, so
// heights and spacings read back bit-identical; NaN marks dropouts. wetroad's own facts that
// X3P has no field for (periodicity, provenance) go to a vendor-specific wetroad.json in the
// archive, named by VendorSpecificID; other readers ignore it.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/core/height_map.hpp"

namespace wr {

// The vendor-specific extension wetroad writes (Record "VendorSpecificID").
inline constexpr const char* kX3pVendorId = "urn:wetroad:x3p-vendor:1";

struct X3pContents {
  HeightMap map;                      // metres; NaN at invalid points; periodic from wetroad.json, else false
  std::string feature_type;           // "SUR" or "PRF"
  char data_type = 'D';               // 'I', 'L', 'F' or 'D'
  std::size_t invalid = 0;            // points marked invalid (NaN or valid.bin)
  double x_offset = 0, y_offset = 0;  // m, position of the first point
  bool checksums_verified = false;    // main.xml's checksum file was present and matched
  std::string creator;                // Record2 Creator or Instrument, when given
  std::vector<std::string> warnings;  // e.g. no checksum file to verify main.xml
};

X3pContents read_x3p(const std::string& path);

// Writes `map` atomically (temporary sibling, then rename); InputError(path, ...) on failure.
// `command` names what made it (Record2's probing-system identification).
void write_x3p(const std::string& path, const HeightMap& map, const std::string& command, const nlohmann::json& provenance);

// True when the first bytes are a zip's local-file signature ("PK\3\4").
bool looks_like_zip(const std::string& path);

}  // namespace wr
