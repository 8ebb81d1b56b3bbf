#pragma once
// VTK XML unstructured grid (.vtu) for ParaView: points (m), cells with VTK type codes, one
// vector point-data array. Binary appended ("raw") data, little endian, 64-bit headers.
// Throws InputError naming `path` when the file cannot be written.
#include <cstdint>
#include <string>
#include <vector>

namespace wr {

// points and point_vectors: 3 doubles per point; connectivity / offsets / types as in VTK's
// UnstructuredGrid (offsets = end of each cell's connectivity).
void write_vtu_file(const std::string& path, const std::vector<double>& points,
                    const std::vector<double>& point_vectors, const std::vector<std::int64_t>& connectivity,
                    const std::vector<std::int64_t>& offsets, const std::vector<std::uint8_t>& types,
                    const std::string& vector_name = "displacement");

// VTK XML image data (.vti) for ParaView: an nx x ny lattice of points at spacing dx, dy (m) in
// the plane z = 0, one scalar Float64 point-data array per entry (nx * ny values each, row-major
// with x fastest, as HeightMap). Binary appended ("raw"), 64-bit headers. Throws InputError
// naming `path` when the file cannot be written; std::invalid_argument for an array of the
// wrong size.
struct VtiArray {
  std::string name;
  const std::vector<double>* values;
};
void write_vti_file(const std::string& path, std::size_t nx, std::size_t ny, double dx, double dy,
                    const std::vector<VtiArray>& arrays);

}  // namespace wr
