#include "water/water_file.hpp"

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
  f.write_attr("/", "summary", summary.dump());
  f.write_attr("/", "provenance", provenance.dump());
  f.commit();
}

}  // namespace wr
