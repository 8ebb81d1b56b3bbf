// libFuzzer: wetroad's HDF5 height-map reader on well-formed HDF5 files whose content is fuzzed:
// the dataset's name, rank, shape and number type; its values (NaN, Inf, huge); the dx, dy,
// unit and periodic attributes in any type and string encoding (or absent); the /synthesis
// record. The file is written with the HDF5 C API, so that what is fuzzed is wetroad's logic
// (units, shapes, spacing, dropouts, synthesis record, memory guards), not libhdf5's parser of
// corrupt containers (fuzz_hdf5_container).
#include <fuzzer/FuzzedDataProvider.h>
#include <hdf5.h>

#include <cmath>
#include <vector>

#include "roads/surface_import.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

hid_t number_type(FuzzedDataProvider& in) {
  static const hid_t* types[] = {&H5T_NATIVE_DOUBLE, &H5T_NATIVE_FLOAT, &H5T_NATIVE_INT, &H5T_NATIVE_SCHAR,
                                 &H5T_NATIVE_ULLONG, &H5T_NATIVE_LLONG};
  return *types[in.ConsumeIntegralInRange<int>(0, 5)];
}

double value(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 5)) {
    case 0: return NAN;
    case 1: return in.ConsumeBool() ? INFINITY : -INFINITY;
    case 2: return in.ConsumeFloatingPointInRange<double>(-1e-3, 1e-3);  // a texture in metres
    case 3: return double(in.ConsumeIntegral<int>());
    default: return in.ConsumeFloatingPoint<double>();
  }
}

// A string attribute in one of the encodings other tools write (see test_import).
void write_string_attribute(hid_t obj, const char* name, const std::string& text, FuzzedDataProvider& in) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_cset(type, in.ConsumeBool() ? H5T_CSET_UTF8 : H5T_CSET_ASCII);
  const hsize_t n = in.ConsumeIntegralInRange<hsize_t>(1, 2);
  const hid_t space = in.ConsumeBool() ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr);
  if (in.ConsumeBool()) {
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* p[2] = {text.c_str(), text.c_str()};
    H5Awrite(a, type, p);
    H5Aclose(a);
  } else {
    const std::size_t size = in.ConsumeIntegralInRange<std::size_t>(1, 16);
    H5Tset_size(type, size);
    const H5T_str_t pads[] = {H5T_STR_NULLTERM, H5T_STR_NULLPAD, H5T_STR_SPACEPAD};
    H5Tset_strpad(type, pads[in.ConsumeIntegralInRange<int>(0, 2)]);
    std::string buf = text;
    buf.resize(2 * size, '\0');
    const hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, buf.data());
    H5Aclose(a);
  }
  H5Sclose(space);
  H5Tclose(type);
}

void write_number_attribute(hid_t obj, const char* name, FuzzedDataProvider& in) {
  const hsize_t n = in.ConsumeIntegralInRange<hsize_t>(1, 3);
  const hid_t space = in.ConsumeBool() ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr);
  const double v[3] = {value(in), value(in), value(in)};
  const hid_t a = H5Acreate2(obj, name, number_type(in), space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, v);  // converted (and clipped) by HDF5 to the stored type
  H5Aclose(a);
  H5Sclose(space);
}

// An attribute that is absent, a number or a string (valid or not for its meaning).
void maybe_attribute(hid_t obj, const char* name, FuzzedDataProvider& in, const std::vector<std::string>& words) {
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: return;
    case 1: write_string_attribute(obj, name, in.ConsumeBool() ? words[in.ConsumeIntegralInRange<std::size_t>(0, words.size() - 1)]
                                                              : in.ConsumeRandomLengthString(12), in);
            return;
    default: write_number_attribute(obj, name, in);
  }
}

}  // namespace

// HDF5 keeps the blocks it frees in its own free lists without a limit: each file it opens
// callocs about a megabyte of cache tables, and handing them back to the system on every close
// made page faults half of this target's time. (wetroad opens one file per command.)
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  H5set_free_list_limits(-1, -1, -1, -1, -1, -1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::string path = wr::fuzz::as_file(nullptr, 0, "map.h5");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  // Built in memory and written out once at close (the core driver): the file is the same.
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_core(fapl, 1 << 16, 1);
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  if (f < 0) __builtin_trap();
  const char* names[] = {"/height", "/profile", "/elevation"};
  const char* name = names[in.ConsumeIntegralInRange<int>(0, 2)];
  const int rank = in.ConsumeIntegralInRange<int>(1, 3);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank), 0), chunk(static_cast<std::size_t>(rank), 4);
  hsize_t count = 1;
  bool small = true;
  // Small shapes, or shapes far beyond memory (which the reader must refuse before allocating);
  // in between, every case would read and analyse millions of fill values.
  for (auto& d : dims) {
    const bool tiny = in.ConsumeBool();
    d = tiny ? in.ConsumeIntegralInRange<hsize_t>(0, 40) : in.ConsumeIntegralInRange<hsize_t>(hsize_t(1) << 32, hsize_t(1) << 40);
    small = small && tiny;
    count = small ? count * d : 0;  // no product of huge sides (it would wrap)
  }
  const hid_t space = H5Screate_simple(rank, dims.data(), nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  const bool stored = small;  // huge shapes are declared, chunked and left unwritten
  if (!stored) H5Pset_chunk(dcpl, rank, chunk.data());
  const hid_t ds = H5Dcreate2(f, name, number_type(in), space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (stored && count > 0) {
    std::vector<double> v(count);
    const double base = value(in);
    for (auto& x : v) x = in.ConsumeBool() ? base : value(in);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  }
  maybe_attribute(ds, "dx", in, {"1e-4"});
  maybe_attribute(ds, "dy", in, {"1e-4"});
  maybe_attribute(ds, "unit", in, {"m", "mm", "um", "\u00b5m", "nm", "MM", " m ", "", "furlong"});
  maybe_attribute(ds, "periodic", in, {"1", "yes"});
  if (in.ConsumeBool()) {
    const hid_t g = H5Gcreate2(f, "/synthesis", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    for (const char* a : {"h0", "hurst", "qL", "q0", "q1", "q1_cut", "plateau_k", "plateau_k_eq44",
                          "h0_eq44_on_lattice", "seed", "oversample", "sampling"})
      maybe_attribute(g, a, in, {"nyquist", "thesis", "other"});
    H5Gclose(g);
  }
  H5Dclose(ds);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(f);
  wr::fuzz::expect_clean([&] { wr::load_surface(path); });
  return 0;
}
