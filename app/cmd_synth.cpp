// `wetroad synth`: write a random-phase self-affine surface (roads/synthesize.hpp) to HDF5.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/synth_options.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "roads/surface_file.hpp"
#include "roads/synthesize.hpp"

namespace wr::app {
namespace {

struct SynthCli {
  std::string output, json, format = "auto";
  SynthOptions surface;
  bool quiet = false;
};

int run_synth(const SynthCli& c) {
  OutputSet outputs;
  if (!c.surface.scene.empty()) outputs.input(scene_path(c.surface.scene));
  const std::string out_path = outputs.add("--output", c.output), json_path = outputs.add("--json", c.json);
  const SurfaceFormat format = output_format(c.output, c.format);
  const SynthParams p = resolve_synth_options(c.surface);
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
                     {"oversample", p.oversample}, {"sampling", sampling_name(p.sampling)},
                     {"seed", p.seed}, {"scene", c.surface.scene}};
  SynthesisRecord rec{r.psd, r.k_eq44, r.h0_eq44_on_lattice, p.seed, p.oversample, p.sampling};
  prov.timings = timer.to_json();
  write_surface_file(out_path, r.map, rec, prov.to_json(), format);
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
                            {"sampling", sampling_name(p.sampling)},
                            {"seed", p.seed},
                            {"timings", timer.to_json()}};
  if (!c.json.empty()) write_text_atomically(json_path, summary.dump(2) + "\n");
  outputs.commit();
  if (!c.quiet) {
    std::printf("wrote %s: %zux%zu surface, dx = %.4g m, L = %.4g m, %zu waves\n", c.output.c_str(),
                r.map.nx, r.map.ny, r.map.dx, r.map.lx(), r.active_waves);
    std::printf("  h0 %.4g m, H %.3g, q0 %.4g 1/m, q1 %.4g 1/m (cut at %.4g), seed %llu\n", p.h0, p.hurst,
                r.psd.q0, r.psd.q1, r.psd.q1_cut, static_cast<unsigned long long>(p.seed));
    std::printf("  plateau k = %.4e m^4 (eq. 4.4 alone: %.4e, would give h0 %+.3f%% on this lattice)\n",
                r.psd.k, r.k_eq44, 100 * eq44_err);
    if (p.sampling == Sampling::thesis)
      std::printf("  thesis sampling: the waves above Nyquist %.4g 1/m are aliased onto the grid (sec. 4.1.1)\n",
                  std::numbers::pi / p.dx);
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
      "and write it as an HDF5 height map (/height, dx, dy; the prescribed PSD in /synthesis) or X3P.\n"
      "The plateau k comes from eq. 4.4 and is then normalised on the lattice, so the measured\n"
      "rms height equals --h0. Same options and seed give a bit-identical map.\n"
      "Example: wetroad synth --scene default -o road.h5\n"
      "         wetroad synth --size 300 --dx 1e-4 --h0 7.08e-4 --q1 62832 --oversample 2 -o c.h5\n"
      "         wetroad synth --size 300 --dx 1e-4 --h0 3.05e-4 --sampling thesis -o a.h5   (the thesis's dataset A)");
  s->add_option("-o,--output", c->output, "output file, HDF5 or X3P (written atomically)")->type_name("OUTPUT")->required();
  s->add_option("--format", c->format,
                "hdf5, x3p (ISO 25178-72, opens in Gwyddion, MountainsMap, openGPS) or auto: x3p for a .x3p name")
      ->capture_default_str();
  add_synth_options(*s, c->surface);
  s->add_option("--json", c->json, "also write a JSON summary of what was generated")->type_name("OUTPUT");
  s->add_option("--threads", c->surface.threads, "worker threads (default: all hardware threads); results do not depend on it")->check(CLI::NonNegativeNumber);
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_synth(*c); }};
}

}  // namespace wr::app
