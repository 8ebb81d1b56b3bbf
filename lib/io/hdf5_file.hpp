#pragma once
// Minimal HDF5 (C API) reading and writing for height maps and results.
//
// Contract: every failure becomes InputError(path, one-line problem); HDF5's own error stack
// printing is switched off. Hdf5Writer writes to a temporary sibling and only commit() makes
// the file appear under its final name; a writer destroyed without commit() leaves nothing.
#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wr {

class Hdf5Reader {
 public:
  explicit Hdf5Reader(const std::string& path);
  ~Hdf5Reader();
  Hdf5Reader(const Hdf5Reader&) = delete;
  Hdf5Reader& operator=(const Hdf5Reader&) = delete;

  const std::string& path() const { return path_; }
  bool has_dataset(const std::string& name) const;
  bool has_group(const std::string& name) const;
  std::vector<std::size_t> dims(const std::string& dataset) const;
  // Reads any numeric dataset converted to double into out[0..count); `count` must equal its
  // element count.
  void read_doubles(const std::string& dataset, double* out, std::size_t count) const;
  // Attributes on an object (group or dataset path, "/" for the root).
  std::optional<double> attr_double(const std::string& object, const std::string& name) const;
  // A string attribute in any encoding (variable or fixed length, any padding, ASCII or UTF-8,
  // scalar or one-element array); nullopt when absent, InputError when present but unreadable.
  std::optional<std::string> attr_string(const std::string& object, const std::string& name) const;
  // A scalar string dataset (write_text, or any encoding as attr_string); throws InputError when
  // absent or not a string.
  std::string read_text(const std::string& dataset) const;

 private:
  std::string path_;
  hid_t file_ = -1;
};

class Hdf5Writer {
 public:
  explicit Hdf5Writer(const std::string& final_path);
  ~Hdf5Writer();  // removes the temporary file unless commit() succeeded
  Hdf5Writer(const Hdf5Writer&) = delete;
  Hdf5Writer& operator=(const Hdf5Writer&) = delete;

  void create_group(const std::string& name);
  void write_matrix(const std::string& name, const double* data, std::size_t ny, std::size_t nx);
  void write_vector(const std::string& name, const double* data, std::size_t n);
  void write_vector(const std::string& name, const std::vector<double>& v) { write_vector(name, v.data(), v.size()); }
  void write_attr(const std::string& object, const std::string& name, double value);
  void write_attr(const std::string& object, const std::string& name, std::int64_t value);
  void write_attr(const std::string& object, const std::string& name, const std::string& value);
  // A scalar string dataset: for text beyond the 64 KiB limit of attributes (JSON records).
  void write_text(const std::string& name, const std::string& text);
  void commit();

 private:
  std::string final_path_;
  std::string tmp_path_;
  hid_t file_ = -1;
  bool committed_ = false;
};

}  // namespace wr
