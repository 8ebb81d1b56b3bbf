// `wetroad fill`: where rain stands on a surface (water/rain_fill.hpp).
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/print_summary.hpp"
#include "lib/core/content_hash.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "roads/surface_file.hpp"
#include "roads/surface_import.hpp"
#include "roads/x3p_file.hpp"
#include "water/rain_fill.hpp"
#include "water/water_file.hpp"

namespace wr::app {
namespace {

struct FillCli {
  std::string input, output, json, tiling = "torus", rule = "fsm", format = "auto";
  double rain = 0, coverage = 0, dmax = 0;
  bool limit = false, stagnant = false, quiet = false;
  int connectivity = 4;
  CLI::Option *rain_opt = nullptr, *coverage_opt = nullptr, *dmax_opt = nullptr;
};

FillRequest make_request(const FillCli& c) {
  FillRequest r;
  if (c.rain_opt->count()) r.rain = c.rain;
  if (c.coverage_opt->count()) r.coverage = c.coverage;
  r.limit = c.limit;
  r.mode = c.stagnant ? WaterMode::stagnant : WaterMode::drained;
  if (c.tiling == "torus")
    r.tiling = Tiling::torus;
  else if (c.tiling == "3x3")
    r.tiling = Tiling::three_by_three;
  else
    throw InputError("--tiling", "must be torus or 3x3");
  if (c.rule == "fsm")
    r.rule = FillRule::fill_spill_merge;
  else if (c.rule == "cap")
    r.rule = FillRule::cap;
  else
    throw InputError("--rule", "must be fsm or cap");
  if (r.rule == FillRule::cap && !(c.dmax > 0 && std::isfinite(c.dmax)))
    throw InputError("--dmax", "--rule cap needs --dmax D > 0 (m)");
  if (r.rule != FillRule::cap && c.dmax_opt->count() > 0)
    throw InputError("--dmax", "applies to --rule cap only; fill-spill-merge has no depth cap");
  r.dmax = c.dmax;
  r.connectivity = c.connectivity;
  return r;
}

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

int run_fill(const FillCli& c) {
  const FillRequest req = make_request(c);
  const SurfaceFormat format = output_format(c.output, c.format);
  OutputSet outputs;
  outputs.input(c.input);
  const std::string out_path = outputs.add("--output", c.output), json_path = outputs.add("--json", c.json);
  PhaseTimer timer;
  timer.start("read");
  // The input's own levels: the wet surface is written at them (nothing removed and restored).
  LoadedSurface s = load_surface(c.input, {}, Levels::keep);
  require_periodic_map(s, "the water module drains periodic tiles");
  print_load_warnings(s);  // also under -q: they are about the data
  timer.start("fill");
  FillResult r = fill_water(s.map, req);
  timer.stop();
  const WaterState& w = r.water;
  nlohmann::json j = {{"coverage", w.coverage},
                      {"rain_depth", num(w.rain_depth)},
                      {"stored_volume", w.stored_volume},
                      {"drained_volume", num(w.drained_volume)},
                      {"lakes", w.lakes},
                      {"mean_depth", w.mean_depth},
                      {"max_depth", w.max_depth},
                      {"mode", req.limit ? "drained-limit" : (req.mode == WaterMode::drained ? "drained" : "stagnant")},
                      {"tiling", c.tiling},
                      {"connectivity", c.connectivity},
                      {"rule", c.rule},
                      {"method", r.method},
                      {"dropouts_filled", s.dropouts},
                      {"hierarchy_nodes", r.hierarchy_nodes},
                      {"warnings", r.warnings},
                      {"dry_surface_sha256", sha256_file_hex(c.input)}};
  if (req.coverage) {
    j["target_coverage"] = *req.coverage;
    j["target_in_jump"] = r.target_in_jump;
    if (r.target_in_jump) j["jump"] = {r.jump_low, r.jump_high};
  }
  if (r.tiling_differing_cells) {
    j["tiling_differing_cells"] = *r.tiling_differing_cells;
    j["tiling_max_difference"] = r.tiling_max_difference;
  }
  nlohmann::json timings = timer.to_json();
  timings["hierarchy"] = r.hierarchy_s;
  timings["water"] = r.fill_s;
  j["timings"] = timings;
  Provenance prov;
  prov.command = "fill";
  prov.inputs = {{"surface", c.input}};
  prov.parameters = {{"rain", c.rain_opt->count() ? nlohmann::json(c.rain) : nlohmann::json(nullptr)},
                     {"coverage", c.coverage_opt->count() ? nlohmann::json(c.coverage) : nlohmann::json(nullptr)},
                     {"limit", c.limit},     {"stagnant", c.stagnant}, {"tiling", c.tiling},
                     {"rule", c.rule},       {"dmax", c.dmax},         {"connectivity", c.connectivity}};
  prov.model = r.method;
  prov.timings = timings;
  j["provenance"] = prov.to_json();
  timer.start("write");
  if (format == SurfaceFormat::x3p) {
    // X3P holds one height field: the wet surface (ground or water level, what a tyre meets).
    HeightMap wet = s.map;
    wet.h = w.level;
    write_x3p(out_path, wet, "fill", {{"summary", j}, {"provenance", prov.to_json()}});
  } else {
    write_water_file(out_path, s.map, w, j, prov.to_json());
  }
  if (!c.json.empty()) write_text_atomically(json_path, j.dump(2) + "\n");
  outputs.commit();
  timer.stop();

  if (!c.quiet) {
    print_import(s);
    std::printf("%s -> %s\n  %s\n", c.input.c_str(), c.output.c_str(), r.method.c_str());
    if (std::isfinite(w.rain_depth)) std::printf("  rain depth        %.6g m\n", w.rain_depth);
    std::printf("  coverage          %.4f %%\n", 100 * w.coverage);
    std::printf("  stored volume     %.6g m (per projected area)\n", w.stored_volume);
    if (std::isfinite(w.drained_volume)) std::printf("  drained volume    %.6g m\n", w.drained_volume);
    std::printf("  lakes             %zu\n  mean depth        %.6g m (wet cells)\n  max depth         %.6g m\n", w.lakes,
                w.mean_depth, w.max_depth);
    if (r.tiling_differing_cells)
      std::printf("  3x3 vs exact      %zu cells differ (max %.3g m)\n", *r.tiling_differing_cells, r.tiling_max_difference);
    if (s.dropouts) std::printf("  note: %zu dropouts were filled before filling with water\n", s.dropouts);
    for (const auto& msg : r.warnings) std::printf("  WARNING: %s\n", msg.c_str());
    std::printf("%s", timer.table().c_str());
    if (r.hierarchy_nodes)
      std::printf("  (depression hierarchy %.4f s, %zu nodes; water %.4f s)\n", r.hierarchy_s, r.hierarchy_nodes, r.fill_s);
  }
  return 0;
}

}  // namespace

Command add_fill(CLI::App& root) {
  auto c = std::make_shared<FillCli>();
  CLI::App* s = root.add_subcommand("fill", "fill a periodic road surface with rain water (drained or stagnant)");
  s->footer(
      "Rain of a uniform depth falls on every cell, runs down the dry surface (steepest descent) into its\n"
      "depression, fills it with a flat water level, spills over the lowest saddle into the neighbour\n"
      "depression, and lakes merge (fill-spill-merge). Drained (default): water leaves only through a lake\n"
      "that reaches its own periodic image, computed exactly on the torus; its large-rain limit (--limit)\n"
      "is every depression at its spill level. Stagnant: periodic and closed, volume conserved, up to a\n"
      "flooded surface. --tiling 3x3 reproduces the thesis's method and reports where it differs from the\n"
      "exact answer. Output HDF5: /height (wet surface), /water_depth, /ground.\n"
      "Example: wetroad fill road.h5 --coverage 0.3 -o wet.h5 --json wet.json");
  s->add_option("surface", c->input, "periodic surface file (HDF5 /height or X3P, e.g. from synth)")->type_name("FILE")->required();
  s->add_option("-o,--output", c->output, "output file (written atomically): HDF5, or X3P of the wet surface")->type_name("OUTPUT")->required();
  s->add_option("--format", c->format,
                "hdf5 (/height, /water_depth, /ground) or x3p (the wet surface only); auto: x3p for a .x3p name")
      ->capture_default_str();
  c->rain_opt = s->add_option("--rain", c->rain, "rain depth in m of water per projected area");
  c->coverage_opt = s->add_option("--coverage", c->coverage,
                                  "target water coverage in (0, 1]: finds the rain depth by bisection");
  s->add_flag("--limit", c->limit, "the drained limit: every depression filled to its spill level");
  s->add_flag("--stagnant", c->stagnant, "periodic and closed: nothing drains (default: drained)");
  s->add_option("--tiling", c->tiling, "torus (exact periodic) or 3x3 (the thesis's approximation)")->capture_default_str();
  s->add_option("--rule", c->rule, "fsm (fill-spill-merge) or cap (thesis's literal rule, non-physical)")
      ->capture_default_str();
  c->dmax_opt = s->add_option("--dmax", c->dmax, "rule cap: level = min(spill level, h + dmax), m");
  s->add_option("--connectivity", c->connectivity, "4 (water crosses cell edges) or 8 (also corners)")
      ->capture_default_str();
  s->add_option("--json", c->json, "also write the summary as JSON")->type_name("OUTPUT");
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_fill(*c); }};
}

}  // namespace wr::app
