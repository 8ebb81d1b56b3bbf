#include "lib/io/vtu_writer.hpp"

#include "lib/core/errors.hpp"

#include <fstream>
#include <stdexcept>

namespace wr {
namespace {

struct Block {
  const void* data;
  std::uint64_t bytes;
};

}  // namespace

void write_vtu_file(const std::string& path, const std::vector<double>& points,
                    const std::vector<double>& point_vectors, const std::vector<std::int64_t>& connectivity,
                    const std::vector<std::int64_t>& offsets, const std::vector<std::uint8_t>& types,
                    const std::string& vector_name) {
  const Block blocks[5] = {{points.data(), points.size() * sizeof(double)},
                           {point_vectors.data(), point_vectors.size() * sizeof(double)},
                           {connectivity.data(), connectivity.size() * sizeof(std::int64_t)},
                           {offsets.data(), offsets.size() * sizeof(std::int64_t)},
                           {types.data(), types.size()}};
  std::uint64_t at[5], pos = 0;
  for (int k = 0; k < 5; ++k) {
    at[k] = pos;
    pos += sizeof(std::uint64_t) + blocks[k].bytes;
  }
  std::ofstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "cannot open for writing");
  f << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << points.size() / 3 << "\" NumberOfCells=\"" << types.size()
    << "\">\n"
    << "<PointData Vectors=\"" << vector_name << "\">\n"
    << "<DataArray type=\"Float64\" Name=\"" << vector_name
    << "\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" << at[1] << "\"/>\n</PointData>\n"
    << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" << at[0]
    << "\"/>\n</Points>\n<Cells>\n"
    << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"" << at[2] << "\"/>\n"
    << "<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"" << at[3] << "\"/>\n"
    << "<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" << at[4] << "\"/>\n"
    << "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  for (const Block& b : blocks) {
    f.write(reinterpret_cast<const char*>(&b.bytes), sizeof b.bytes);
    f.write(static_cast<const char*>(b.data), std::streamsize(b.bytes));
  }
  f << "\n</AppendedData>\n</VTKFile>\n";
  if (!f) throw InputError(path, "write failed (disk full?)");
}

void write_vti_file(const std::string& path, std::size_t nx, std::size_t ny, double dx, double dy,
                    const std::vector<VtiArray>& arrays) {
  for (const VtiArray& a : arrays)
    if (a.values->size() != nx * ny) throw std::invalid_argument("write_vti_file: array " + a.name + " has the wrong size");
  std::ofstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "cannot open for writing");
  f.precision(17);  // the spacings exactly
  f << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "<ImageData WholeExtent=\"0 " << nx - 1 << " 0 " << ny - 1 << " 0 0\" Origin=\"0 0 0\" Spacing=\"" << dx << " "
    << dy << " 1\">\n<Piece Extent=\"0 " << nx - 1 << " 0 " << ny - 1 << " 0 0\">\n<PointData>\n";
  std::uint64_t pos = 0;
  for (const VtiArray& a : arrays) {
    f << "<DataArray type=\"Float64\" Name=\"" << a.name << "\" format=\"appended\" offset=\"" << pos << "\"/>\n";
    pos += sizeof(std::uint64_t) + a.values->size() * sizeof(double);
  }
  f << "</PointData>\n</Piece>\n</ImageData>\n<AppendedData encoding=\"raw\">\n_";
  for (const VtiArray& a : arrays) {
    const std::uint64_t bytes = a.values->size() * sizeof(double);
    f.write(reinterpret_cast<const char*>(&bytes), sizeof bytes);
    f.write(reinterpret_cast<const char*>(a.values->data()), std::streamsize(bytes));
  }
  f << "\n</AppendedData>\n</VTKFile>\n";
  if (!f) throw InputError(path, "write failed (disk full?)");
}

}  // namespace wr
