#pragma once
// The synthesis options shared by `wetroad synth` and the sweeps: a scene file of defaults
// (share/scenes/, 'default' = the thesis's asphalt-like surface) overridden by the options given.
#include <cstdint>
#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "roads/synthesize.hpp"

namespace wr::app {

struct SynthOptions {
  std::string scene;
  std::size_t size = 0, nx = 0, ny = 0;
  double dx = 0, h0 = 0, hurst = 0, q0_ratio = 0, q1 = 0, q1_fraction = 0;
  int oversample = 1, threads = 0;
  Sampling sampling = Sampling::nyquist;
  std::int64_t seed = 1;  // signed, so that "-1" is read as -1 and refused, not wrapped to 2^64 - 1
  std::map<std::string, CLI::Option*> opts;
  bool given(const std::string& name) const { return opts.at(name)->count() > 0; }
  bool any_given() const;  // any synthesis option (or --scene) on the command line
};

// Registers --scene, --size, --nx, --ny, --dx, --h0, --hurst, --q0-ratio, --q1, --q1-fraction,
// --oversample, --sampling and --seed on `app`.
void add_synth_options(CLI::App& app, SynthOptions& o);

// Scene file first, then every option the user gave. Throws InputError naming the scene file
// when it cannot be read.
SynthParams resolve_synth_options(const SynthOptions& o);

// share/scenes/default-asphalt.json for "default", else the name itself (a path).
std::string scene_path(const std::string& name);

}  // namespace wr::app
