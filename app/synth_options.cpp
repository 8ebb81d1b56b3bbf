#include "app/synth_options.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "lib/core/errors.hpp"

namespace wr::app {

std::string scene_path(const std::string& name) {
  if (name == "default") return std::string(WETROAD_SHARE_DIR) + "/scenes/default-asphalt.json";
  return name;
}

namespace {

// A whole number of a scene file, in T's range: nlohmann's get<T> casts a float such as 1e29
// to an integer type unchecked (undefined behaviour); anything but an integer in range is an error.
template <class T>
T whole_number(const nlohmann::json& s, const char* key, T fallback) {
  if (!s.contains(key)) return fallback;
  const nlohmann::json& v = s[key];
  const auto out_of_range = [&] { return std::runtime_error(std::string("\"") + key + "\" is out of range"); };
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) throw out_of_range();
    return static_cast<T>(u);
  }
  if (v.is_number_integer()) {
    const auto i = v.get<std::int64_t>();
    if (i < 0 && !std::numeric_limits<T>::is_signed) throw out_of_range();
    if (i < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
        static_cast<std::uint64_t>(std::max<std::int64_t>(i, 0)) > static_cast<std::uint64_t>(std::numeric_limits<T>::max()))
      throw out_of_range();
    return static_cast<T>(i);
  }
  throw std::runtime_error(std::string("\"") + key + "\" must be a whole number");
}

}  // namespace

bool SynthOptions::any_given() const {
  for (const auto& [name, opt] : opts)
    if (opt->count() > 0) return true;
  return false;
}

void add_synth_options(CLI::App& s, SynthOptions& c) {
  c.opts["--scene"] = s.add_option("--scene", c.scene,
                                   "scene JSON with a \"surface\" block of defaults ('default' = "
                                   "share/scenes/default-asphalt.json); options given here override it")->type_name("FILE");
  c.opts["--size"] = s.add_option("--size", c.size, "grid points per side, N (default 300)");
  c.opts["--nx"] = s.add_option("--nx", c.nx, "grid points along x (overrides --size)");
  c.opts["--ny"] = s.add_option("--ny", c.ny, "grid points along y (overrides --size)");
  c.opts["--dx"] = s.add_option("--dx", c.dx, "grid spacing in m, same in x and y (default 1e-4)");
  c.opts["--h0"] = s.add_option("--h0", c.h0, "rms height in m (default 3e-4)");
  c.opts["--hurst"] = s.add_option("--hurst", c.hurst, "Hurst exponent H in (0,1) (default 0.7)");
  c.opts["--q0-ratio"] = s.add_option("--q0-ratio", c.q0_ratio, "roll-off q0 / qL, qL = 2 pi / L (default 5)");
  c.opts["--q1"] = s.add_option("--q1", c.q1,
                                "short-distance cut-off in 1/m (default: the grid Nyquist pi/dx; 2 pi/dx under "
                                "--sampling thesis); above Nyquist it is refused unless --oversample makes the grid "
                                "fine enough or --sampling thesis aliases it on purpose");
  c.opts["--q1-fraction"] = s.add_option("--q1-fraction", c.q1_fraction,
                                         "low-pass: keep q <= f q1 without renormalising, so h0 drops "
                                         "(thesis dataset C: 1, 1/2, 1/4, 1/8) (default 1)");
  c.opts["--oversample"] = s.add_option("--oversample", c.oversample,
                                        "generate on a grid S times finer (N S points at dx / S) (default 1)");
  c.opts["--sampling"] =
      s.add_option("--sampling", c.sampling,
                   "nyquist (band-limited: no wave above the grid's Nyquist pi/dx) or thesis (the thesis's surfaces, "
                   "sec. 4.1.1 and Table 5.1: waves up to q1 = 2 pi/dx summed at the grid points, so those above "
                   "Nyquist alias onto lower wavenumbers; ~8 % steeper lattice at dataset A's spectrum)")
          ->transform(CLI::CheckedTransformer(sampling_names(), CLI::ignore_case))
          ->option_text("nyquist|thesis (default nyquist)");
  c.opts["--seed"] = s.add_option("--seed", c.seed, "random seed of the phases (default 1)");
}

SynthParams resolve_synth_options(const SynthOptions& c) {
  SynthParams p;
  if (!c.scene.empty()) {
    const std::string path = scene_path(c.scene);
    std::ifstream in(path);
    if (!in) throw InputError(path, "cannot open scene file");
    nlohmann::json j;
    try {
      in >> j;
    } catch (const std::exception& e) {
      throw InputError(path, std::string("not valid JSON: ") + e.what());
    }
    if (!j.is_object()) throw InputError(path, "a scene file is a JSON object with a \"surface\" block");
    const auto s = j.value("surface", nlohmann::json::object());
    if (!s.is_object()) throw InputError(path, "\"surface\" must be an object of synthesis options");
    // A misspelled key would leave its default in force without a word: every key is known.
    for (const auto& [key, value] : j.items())
      if (key != "surface" && key != "description" && key != "source")
        throw InputError(path, "unknown key \"" + key + "\" (a scene file holds \"surface\" and \"description\")");
    static const char* const kSurfaceKeys[] = {"size", "nx", "ny", "dx", "h0", "hurst", "q0_ratio", "q1",
                                               "q1_fraction", "oversample", "sampling", "seed"};
    for (const auto& [key, value] : s.items())
      if (std::find(std::begin(kSurfaceKeys), std::end(kSurfaceKeys), key) == std::end(kSurfaceKeys))
        throw InputError(path, "unknown key \"" + key + "\" in \"surface\" (known: size, nx, ny, dx, h0, hurst, "
                               "q0_ratio, q1, q1_fraction, oversample, sampling, seed)");
    try {
      if (s.contains("size")) p.nx = p.ny = whole_number<std::size_t>(s, "size", 0);
      p.nx = whole_number(s, "nx", p.nx);
      p.ny = whole_number(s, "ny", p.ny);
      p.dx = s.value("dx", p.dx);
      p.h0 = s.value("h0", p.h0);
      p.hurst = s.value("hurst", p.hurst);
      p.q0_ratio = s.value("q0_ratio", p.q0_ratio);
      if (s.contains("q1")) p.q1 = s["q1"].get<double>();
      p.q1_fraction = s.value("q1_fraction", p.q1_fraction);
      p.oversample = whole_number(s, "oversample", p.oversample);
      if (s.contains("sampling")) {
        const std::string name = s["sampling"].get<std::string>();
        const auto sampling = sampling_from_name(name);
        // Wrapped with the file's name by the catch below.
        if (!sampling) throw std::runtime_error("\"sampling\" must be nyquist or thesis, not \"" + name + "\"");
        p.sampling = *sampling;
      }
      p.seed = whole_number(s, "seed", p.seed);
    } catch (const std::exception& e) {
      throw InputError(path, std::string("bad value in \"surface\": ") + e.what());
    }
  }
  if (c.given("--size")) p.nx = p.ny = c.size;
  if (c.given("--nx")) p.nx = c.nx;
  if (c.given("--ny")) p.ny = c.ny;
  if (c.given("--dx")) p.dx = c.dx;
  if (c.given("--h0")) p.h0 = c.h0;
  if (c.given("--hurst")) p.hurst = c.hurst;
  if (c.given("--q0-ratio")) p.q0_ratio = c.q0_ratio;
  if (c.given("--q1")) p.q1 = c.q1;
  if (c.given("--q1-fraction")) p.q1_fraction = c.q1_fraction;
  if (c.given("--oversample")) p.oversample = c.oversample;
  if (c.given("--sampling")) p.sampling = c.sampling;
  if (c.given("--seed")) {
    if (c.seed < 0) throw InputError("--seed", "must be a whole number in 0 ... " + std::to_string(kMaxSeed));
    p.seed = static_cast<std::uint64_t>(c.seed);
  }
  p.threads = c.threads;
  return p;
}

}  // namespace wr::app
