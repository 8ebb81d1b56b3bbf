// `wetroad synth`: write a random-phase self-affine surface (roads/synthesize.hpp) to HDF5.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/io/atomic_output.hpp"
#include "roads/surface_file.hpp"
#include "roads/synthesize.hpp"

namespace wr::app {
namespace {

struct SynthCli {
  std::string output, json, scene;
  std::size_t size = 0, nx = 0, ny = 0;
  double dx = 0, h0 = 0, hurst = 0, q0_ratio = 0, q1 = 0, q1_fraction = 0;
  int oversample = 1, threads = 0;
  std::uint64_t seed = 1;
  bool quiet = false;
  std::map<std::string, CLI::Option*> opts;
  bool given(const std::string& name) const { return opts.at(name)->count() > 0; }
};

std::string scene_path(const std::string& name) {
  if (name == "default") return std::string(WETROAD_SHARE_DIR) + "/scenes/default-asphalt.json";
  return name;
}

// Scene file first, then every option the user gave on the command line.
SynthParams resolve(const SynthCli& c) {
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
    const auto s = j.value("surface", nlohmann::json::object());
    try {
      if (s.contains("size")) p.nx = p.ny = s["size"].get<std::size_t>();
      p.nx = s.value("nx", p.nx);
      p.ny = s.value("ny", p.ny);
      p.dx = s.value("dx", p.dx);
      p.h0 = s.value("h0", p.h0);
      p.hurst = s.value("hurst", p.hurst);
      p.q0_ratio = s.value("q0_ratio", p.q0_ratio);
      if (s.contains("q1")) p.q1 = s["q1"].get<double>();
      p.q1_fraction = s.value("q1_fraction", p.q1_fraction);
      p.oversample = s.value("oversample", p.oversample);
      p.seed = s.value("seed", p.seed);
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
  if (c.given("--seed")) p.seed = c.seed;
  p.threads = c.threads;
  return p;
}

int run_synth(const SynthCli& c) {
  const SynthParams p = resolve(c);
  PhaseTimer timer;
  timer.start("synthesize");
  const SynthResult r = synthesize(p);
  timer.start("write");
  Provenance prov;
  prov.command = "synth";
  prov.model = "random-phase self-affine PSD (thesis eq. 3.85, 4.4), lattice-normalised";
  prov.parameters = {{"nx", p.nx},         {"ny", p.ny},           {"dx", p.dx},
                     {"h0", p.h0},         {"hurst", p.hurst},     {"q0_ratio", p.q0_ratio},
                     {"q1", r.psd.q1},     {"q1_fraction", p.q1_fraction},
                     {"oversample", p.oversample}, {"seed", p.seed}, {"scene", c.scene}};
  SynthesisRecord rec{r.psd, r.k_eq44, r.h0_eq44_on_lattice, p.seed, p.oversample};
  prov.timings = timer.to_json();
  write_surface_file(c.output, r.map, rec, prov.to_json());
  timer.stop();

  const double eq44_err = r.h0_eq44_on_lattice / p.h0 - 1;
  nlohmann::json summary = {{"output", c.output},
                            {"nx", r.map.nx},
                            {"ny", r.map.ny},
                            {"dx", r.map.dx},
                            {"dy", r.map.dy},
                            {"h0", p.h0},
                            {"hurst", p.hurst},
                            {"qL", r.psd.qL},
                            {"q0", r.psd.q0},
                            {"q1", r.psd.q1},
                            {"q1_cut", r.psd.q1_cut},
                            {"plateau_k", r.psd.k},
                            {"plateau_k_eq44", r.k_eq44},
                            {"h0_eq44_on_lattice", r.h0_eq44_on_lattice},
                            {"eq44_h0_error", eq44_err},
                            {"waves", r.active_waves},
                            {"seed", p.seed},
                            {"timings", timer.to_json()}};
  if (!c.json.empty()) write_text_atomically(c.json, summary.dump(2) + "\n");
  if (!c.quiet) {
    std::printf("wrote %s: %zux%zu surface, dx = %.4g m, L = %.4g m, %zu waves\n", c.output.c_str(),
                r.map.nx, r.map.ny, r.map.dx, r.map.lx(), r.active_waves);
    std::printf("  h0 %.4g m, H %.3g, q0 %.4g 1/m, q1 %.4g 1/m (cut at %.4g), seed %llu\n", p.h0, p.hurst,
                r.psd.q0, r.psd.q1, r.psd.q1_cut, static_cast<unsigned long long>(p.seed));
    std::printf("  plateau k = %.4e m^4 (eq. 4.4 alone: %.4e, would give h0 %+.3f%% on this lattice)\n",
                r.psd.k, r.k_eq44, 100 * eq44_err);
    std::printf("%s", timer.table().c_str());
  }
  return 0;
}

}  // namespace

Command add_synth(CLI::App& root) {
  auto c = std::make_shared<SynthCli>();
  CLI::App* s = root.add_subcommand("synth", "synthesize a self-affine road surface from its power spectrum");
  s->footer(
      "Synthesize a periodic, isotropic, self-affine surface by random-phase FFT (thesis sec. 4.1)\n"
      "and write it as an HDF5 height map (/height, dx, dy; the prescribed PSD in /synthesis).\n"
      "The plateau k comes from eq. 4.4 and is then normalised on the lattice, so the measured\n"
      "rms height equals --h0. Same options and seed give a bit-identical map.\n"
      "Example: wetroad synth --scene default -o road.h5\n"
      "         wetroad synth --size 300 --dx 1e-4 --h0 7.08e-4 --q1 62832 --oversample 2 -o c.h5");
  s->add_option("-o,--output", c->output, "output HDF5 file (written atomically)")->required();
  c->opts["--scene"] = s->add_option("--scene", c->scene,
                                     "scene JSON with a \"surface\" block of defaults ('default' = "
                                     "share/scenes/default-asphalt.json); options given here override it");
  c->opts["--size"] = s->add_option("--size", c->size, "grid points per side, N (default 300)");
  c->opts["--nx"] = s->add_option("--nx", c->nx, "grid points along x (overrides --size)");
  c->opts["--ny"] = s->add_option("--ny", c->ny, "grid points along y (overrides --size)");
  c->opts["--dx"] = s->add_option("--dx", c->dx, "grid spacing in m, same in x and y (default 1e-4)");
  c->opts["--h0"] = s->add_option("--h0", c->h0, "rms height in m (default 3e-4)");
  c->opts["--hurst"] = s->add_option("--hurst", c->hurst, "Hurst exponent H in (0,1) (default 0.7)");
  c->opts["--q0-ratio"] = s->add_option("--q0-ratio", c->q0_ratio, "roll-off q0 / qL, qL = 2 pi / L (default 5)");
  c->opts["--q1"] = s->add_option("--q1", c->q1,
                                  "short-distance cut-off in 1/m (default: the grid Nyquist pi/dx); above "
                                  "Nyquist it is refused unless --oversample makes the grid fine enough");
  c->opts["--q1-fraction"] = s->add_option("--q1-fraction", c->q1_fraction,
                                           "low-pass: keep q <= f q1 without renormalising, so h0 drops "
                                           "(thesis dataset C: 1, 1/2, 1/4, 1/8) (default 1)");
  c->opts["--oversample"] = s->add_option("--oversample", c->oversample,
                                          "generate on a grid S times finer (N S points at dx / S) (default 1)");
  c->opts["--seed"] = s->add_option("--seed", c->seed, "random seed of the phases (default 1)");
  s->add_option("--json", c->json, "also write a JSON summary of what was generated");
  s->add_option("--threads", c->threads, "worker threads (default: all hardware threads); results do not depend on it");
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_synth(*c); }};
}

}  // namespace wr::app
