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

}  // namespace wr
