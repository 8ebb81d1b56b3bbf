#include "lib/io/hdf5_file.hpp"

#include <cstdio>
#include <filesystem>

#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"

namespace wr {
namespace {

void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

// Closes an HDF5 identifier with the right function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*closer_)(hid_t);
};

bool link_exists(hid_t file, const std::string& name) {
  if (name == "/") return true;
  // Walk the path so that a missing intermediate group is "absent", not an error.
  std::string partial;
  std::size_t pos = 0;
  while (pos < name.size()) {
    std::size_t next = name.find('/', pos + 1);
    partial = name.substr(0, next);
    if (!partial.empty() && partial != "/" && H5Lexists(file, partial.c_str(), H5P_DEFAULT) <= 0)
      return false;
    if (next == std::string::npos) break;
    pos = next;
  }
  return true;
}

H5O_type_t object_type(hid_t file, const std::string& name) {
  H5O_info_t info;
  if (H5Oget_info_by_name(file, name.c_str(), &info, H5P_DEFAULT) < 0) return H5O_TYPE_UNKNOWN;
  return info.type;
}

// One string value of an attribute or dataset (`obj`), whatever encoding the writer chose:
// variable length (h5py's default) or fixed length; null-terminated, null-padded or
// space-padded; ASCII or UTF-8; a scalar or a one-element array. The value is read in the
// file's own string type (no conversion: HDF5 refuses ASCII <-> UTF-8 conversions, and a
// null-terminated memory type of the stored size drops the last character of a null-padded
// string), then the padding is stripped by the file's rule.
std::string read_string_value(hid_t obj, hid_t type, hid_t space, const std::string& path, const std::string& what) {
  const bool is_attribute = H5Iget_type(obj) == H5I_ATTR;
  if (H5Tget_class(type) != H5T_STRING) throw InputError(path, what + " is not a string");
  if (H5Sget_simple_extent_npoints(space) != 1) throw InputError(path, what + " is not a single string");
  Handle mem(H5Tcopy(type), H5Tclose);
  auto read = [&](void* buf) {
    return is_attribute ? H5Aread(obj, mem.get(), buf) : H5Dread(obj, mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  };
  if (H5Tis_variable_str(type) > 0) {
    char* s = nullptr;
    if (read(&s) < 0) throw InputError(path, "cannot read " + what);
    std::string out = s ? s : "";
    if (s) {
      // Variable-length data is freed through the same memory type and space it was read with.
      H5Dvlen_reclaim(mem.get(), space, H5P_DEFAULT, &s);
    }
    return out;
  }
  const std::size_t n = H5Tget_size(type);
  std::string out(n, '\0');
  if (n > 0 && read(out.data()) < 0) throw InputError(path, "cannot read " + what);
  const H5T_str_t pad = H5Tget_strpad(type);
  if (pad == H5T_STR_SPACEPAD) {
    out.erase(out.find_last_not_of(' ') + 1);
  } else if (const auto nul = out.find('\0'); nul != std::string::npos) {
    out.resize(nul);  // null-terminated or null-padded: the value ends at the first NUL
  }
  return out;
}

}  // namespace

Hdf5Reader::Hdf5Reader(const std::string& path) : path_(path) {
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a file");
  const htri_t is_h5 = H5Fis_hdf5(path.c_str());
  if (is_h5 <= 0) throw InputError(path, "not an HDF5 file");
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw InputError(path, "cannot open HDF5 file (permissions or corrupt file)");
}

Hdf5Reader::~Hdf5Reader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool Hdf5Reader::has_dataset(const std::string& name) const {
  return link_exists(file_, name) && object_type(file_, name) == H5O_TYPE_DATASET;
}

bool Hdf5Reader::has_group(const std::string& name) const {
  return link_exists(file_, name) && object_type(file_, name) == H5O_TYPE_GROUP;
}

std::vector<std::size_t> Hdf5Reader::dims(const std::string& dataset) const {
  Handle ds(H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) throw InputError(path_, "cannot open dataset " + dataset);
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw InputError(path_, "cannot read the shape of " + dataset);
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
  return {d.begin(), d.end()};
}

void Hdf5Reader::read_doubles(const std::string& dataset, double* out, std::size_t count) const {
  Handle ds(H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) throw InputError(path_, "cannot open dataset " + dataset);
  Handle type(H5Dget_type(ds.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw InputError(path_, "dataset " + dataset + " is not numeric");
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  if (static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get())) != count)
    throw InputError(path_, "dataset " + dataset + " does not hold the expected number of values");
  if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
    throw InputError(path_, "cannot read dataset " + dataset + " (corrupt or truncated file)");
}

std::string Hdf5Reader::read_text(const std::string& dataset) const {
  Handle ds(H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) throw InputError(path_, "cannot open dataset " + dataset);
  Handle type(H5Dget_type(ds.get()), H5Tclose);
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  return read_string_value(ds.get(), type.get(), space.get(), path_, "dataset " + dataset);
}

std::optional<double> Hdf5Reader::attr_double(const std::string& object,
                                              const std::string& name) const {
  if (!link_exists(file_, object)) return std::nullopt;
  if (H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  Handle a(H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!a.ok()) return std::nullopt;
  Handle type(H5Aget_type(a.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw InputError(path_, "attribute " + name + " of " + object + " is not a number");
  Handle space(H5Aget_space(a.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw InputError(path_, "attribute " + name + " of " + object + " is not a scalar");
  double v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    throw InputError(path_, "cannot read attribute " + name + " of " + object);
  return v;
}

std::optional<std::string> Hdf5Reader::attr_string(const std::string& object,
                                                   const std::string& name) const {
  if (!link_exists(file_, object)) return std::nullopt;
  if (H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  Handle a(H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!a.ok()) throw InputError(path_, "cannot open attribute " + name + " of " + object);
  Handle type(H5Aget_type(a.get()), H5Tclose);
  Handle space(H5Aget_space(a.get()), H5Sclose);
  return read_string_value(a.get(), type.get(), space.get(), path_, "attribute " + name + " of " + object);
}

Hdf5Writer::Hdf5Writer(const std::string& final_path)
    : final_path_(final_path), tmp_path_(temporary_sibling(final_path)) {
  silence_hdf5();
  file_ = H5Fcreate(tmp_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) throw InputError(final_path, "cannot create file (directory missing or not writable)");
}

Hdf5Writer::~Hdf5Writer() {
  if (file_ >= 0) H5Fclose(file_);
  if (!committed_) std::remove(tmp_path_.c_str());
}

void Hdf5Writer::create_group(const std::string& name) {
  Handle g(H5Gcreate2(file_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.ok()) throw InputError(final_path_, "cannot create group " + name);
}

namespace {
void write_dataset(hid_t file, const std::string& path, const std::string& name, const hsize_t* dims, int rank,
                   const double* data) {
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  Handle ds(H5Dcreate2(file, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
            H5Dclose);
  if (!ds.ok() || H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw InputError(path, "cannot write dataset " + name + " (disk full?)");
}
}  // namespace

void Hdf5Writer::write_matrix(const std::string& name, const double* data, std::size_t ny, std::size_t nx) {
  const hsize_t d[2] = {ny, nx};
  write_dataset(file_, final_path_, name, d, 2, data);
}

void Hdf5Writer::write_vector(const std::string& name, const double* data, std::size_t n) {
  const hsize_t d[1] = {n};
  write_dataset(file_, final_path_, name, d, 1, data);
}

namespace {
void write_attr_raw(hid_t file, const std::string& path, const std::string& object,
                    const std::string& name, hid_t file_type, hid_t mem_type, const void* value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT) > 0)
    H5Adelete_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT);
  Handle a(H5Acreate_by_name(file, object.c_str(), name.c_str(), file_type, space.get(), H5P_DEFAULT,
                             H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (!a.ok() || H5Awrite(a.get(), mem_type, value) < 0)
    throw InputError(path, "cannot write attribute " + name + " on " + object);
}
}  // namespace

void Hdf5Writer::write_attr(const std::string& object, const std::string& name, double value) {
  write_attr_raw(file_, final_path_, object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5Writer::write_attr(const std::string& object, const std::string& name, std::int64_t value) {
  write_attr_raw(file_, final_path_, object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void Hdf5Writer::write_attr(const std::string& object, const std::string& name,
                            const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.size() + 1);  // room for the terminating NUL
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  write_attr_raw(file_, final_path_, object, name, type.get(), type.get(), value.c_str());
}

void Hdf5Writer::write_text(const std::string& name, const std::string& text) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), text.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle ds(H5Dcreate2(file_, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!ds.ok() || H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()) < 0)
    throw InputError(final_path_, "cannot write dataset " + name + " (disk full?)");
}

void Hdf5Writer::commit() {
  if (H5Fclose(file_) < 0) {
    file_ = -1;
    throw InputError(final_path_, "cannot finish writing (disk full?)");
  }
  file_ = -1;
  commit_file(tmp_path_, final_path_);
  committed_ = true;
}

}  // namespace wr
