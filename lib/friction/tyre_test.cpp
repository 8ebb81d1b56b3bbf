#include "lib/friction/tyre_test.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"
#include "lib/io/input_file.hpp"

namespace wr {
namespace {

TyreTest e274(const std::string& name, double drainage, const std::string& tyre) {
  TyreTest t;
  t.name = name;
  t.source = "ASTM E274 locked wheel, " + tyre + " (built in; docs/friction-model.md)";
  t.drainage_length = drainage;
  return t;
}

double positive_key(const nlohmann::json& j, const std::string& key, const std::string& path, double lo, double hi,
                    bool required, double fallback) {
  if (!j.contains(key)) {
    if (required) throw InputError(path, "missing key \"" + key + "\"");
    return fallback;
  }
  if (!j[key].is_number()) throw InputError(path, key + ": must be a number");
  const double v = j[key].get<double>();
  if (!(v >= lo && v <= hi)) throw InputError(path, key + ": must lie in " + number_text(lo) + " ... " + number_text(hi) + ", got " + number_text(v));
  return v;
}

}  // namespace

TyreTest tyre_test(const std::string& name_or_file) {
  if (name_or_file == "e274-ribbed") return e274("e274-ribbed", 0.018, "ASTM E501 standard rib tyre");
  if (name_or_file == "e274-smooth") return e274("e274-smooth", 0.15, "ASTM E524 standard smooth tyre");
  const std::string& path = name_or_file;
  const std::string text = read_input_file(path, "tyre test file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("not JSON (") + e.what() + "); --test takes e274-ribbed, e274-smooth or a JSON file");
  }
  if (!j.is_object()) throw InputError(path, "a tyre test file holds one JSON object");
  static const char* known[] = {"name", "source", "patch_length_m", "drainage_length_m", "slip_speed_m_s", "water_film_m"};
  for (const auto& [k, v] : j.items())
    if (std::find(std::begin(known), std::end(known), k) == std::end(known)) throw InputError(path, "unknown key \"" + k + "\"");
  TyreTest t;
  if (!j.contains("name") || !j["name"].is_string() || j["name"].get<std::string>().empty())
    throw InputError(path, "missing key \"name\" (a non-empty string)");
  t.name = j["name"].get<std::string>();
  t.source = j.contains("source") && j["source"].is_string() ? j["source"].get<std::string>() : path;
  t.patch_length = positive_key(j, "patch_length_m", path, 0.005, 2.0, true, 0);
  t.drainage_length = positive_key(j, "drainage_length_m", path, 1e-4, 2.0, true, 0);
  t.slip_speed = positive_key(j, "slip_speed_m_s", path, 0.1, 150.0, true, 0);
  t.water_film = positive_key(j, "water_film_m", path, 1e-9, kMaxWaterFilm, false, t.water_film);
  return t;
}

void check_water_film(double film, const std::string& option) {
  if (!(film > 0 && film <= kMaxWaterFilm))
    throw InputError(option, "the water film must be a depth in (0, " + number_text(kMaxWaterFilm) +
                                 "] m (ASTM E274's is 0.5e-3; deeper water than a tread groove is dynamic hydroplaning, "
                                 "not modelled), got " + number_text(film));
}

double water_viscosity(double celsius) {
  const double t = std::clamp(celsius, 0.0, 100.0) + 273.15;
  return 2.414e-5 * std::pow(10.0, 247.8 / (t - 140));
}

}  // namespace wr
