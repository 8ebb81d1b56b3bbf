#include "water/water_file.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "lib/core/big_buffer.hpp"
#include "lib/core/content_hash.hpp"
#include "lib/core/errors.hpp"
#include "lib/io/hdf5_file.hpp"

namespace wr {

void write_water_file(const std::string& path, const HeightMap& ground, const WaterState& w,
                      const nlohmann::json& summary, const nlohmann::json& provenance) {
  Hdf5Writer f(path);
  BigVector depth(ground.h.size());
  for (std::size_t c = 0; c < depth.size(); ++c) depth[c] = w.level[c] - ground.h[c];
  const struct {
    const char* name;
    const double* data;
  } fields[] = {{"/height", w.level.data()}, {"/water_depth", depth.data()}, {"/ground", ground.h.data()}};
  for (const auto& fld : fields) {
    f.write_matrix(fld.name, fld.data, ground.ny, ground.nx);
    f.write_attr(fld.name, "dx", ground.dx);
    f.write_attr(fld.name, "dy", ground.dy);
    f.write_attr(fld.name, "unit", std::string("m"));
    f.write_attr(fld.name, "periodic", static_cast<std::int64_t>(ground.periodic ? 1 : 0));
  }
  for (const auto& [key, value] : summary.items()) {
    if (value.is_number()) f.write_attr("/", key, value.get<double>());
    if (value.is_string()) f.write_attr("/", key, value.get<std::string>());
  }
  if (!summary.contains("dry_surface_sha256"))
    throw std::logic_error("write_water_file: the summary lacks dry_surface_sha256");
  f.write_attr("/", "summary", summary.dump());
  f.write_attr("/", "provenance", provenance.dump());
  f.commit();
}

namespace {

bool starts_with_zip_magic(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  char m[4] = {};
  const bool zip = std::fread(m, 1, 4, f) == 4 && m[0] == 'P' && m[1] == 'K' && m[2] == 3 && m[3] == 4;
  std::fclose(f);
  return zip;
}

}  // namespace

double check_wet_file(const std::string& wet_path, const std::string& dry_path) {
  const std::string takes = "--wet takes the HDF5 output of `wetroad fill` run on " + dry_path;
  if (starts_with_zip_magic(wet_path))
    throw InputError(wet_path, "an X3P file holds the wet surface only; " + takes);
  Hdf5Reader r(wet_path);
  for (const char* name : {"/height", "/water_depth", "/ground"})
    if (!r.has_dataset(name)) throw InputError(wet_path, std::string("no ") + name + " (a dry surface?); " + takes);
  const std::vector<std::size_t> d = r.dims("/water_depth");
  if (r.dims("/height") != d || r.dims("/ground") != d)
    throw InputError(wet_path, "/height, /water_depth and /ground differ in shape; not a file of `wetroad fill`");
  const std::optional<std::string> tie = r.attr_string("/", "dry_surface_sha256");
  if (!tie)
    throw InputError(wet_path, "does not record its dry surface (written by an older wetroad?); run `wetroad fill " +
                                   dry_path + "` again");
  if (*tie != sha256_file_hex(dry_path))
    throw InputError(wet_path, "was filled from another surface than " + dry_path +
                                   " (its recorded SHA-256 differs); give the surface it was made from");
  std::size_t n = 1;
  for (std::size_t x : d) n *= x;
  BigVector depth(n);
  r.read_doubles("/water_depth", depth.data(), n);
  std::size_t wet = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(depth[i]) || depth[i] < 0)
      throw InputError(wet_path, "/water_depth holds " + std::to_string(depth[i]) + " at cell " + std::to_string(i) +
                                     "; water depths are finite and >= 0");
    wet += depth[i] > 0;
  }
  return n ? static_cast<double>(wet) / static_cast<double>(n) : 0.0;
}

}  // namespace wr
