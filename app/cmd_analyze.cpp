// `wetroad analyze FILE`: texture statistics of a surface (roads/analyze.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/print_summary.hpp"
#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "roads/analyze.hpp"
#include "roads/surface_import.hpp"

namespace wr::app {
namespace {

struct AnalyzeCli {
  std::string input, json, out, unit = "m", mpd_method = "auto";
  double dx = 0, dy = 0;
  bool periodic = false, quiet = false, no_expected_mpd = false, keep_plates = false, points = false;
  double max_gap = 0;
  double evaluation_length = 10.0;  // m; the default applies to 1-D profiles only
  int threads = 0;
  MpdOptions mpd;
  CLI::Option *dx_opt = nullptr, *dy_opt = nullptr, *max_gap_opt = nullptr, *evaluation_opt = nullptr;
  std::vector<CLI::Option*> text_only;  // --dx --dy --unit --points --max-gap --periodic
};

// MPD per evaluation length (ISO 13473-1:2019 reports a continuous record per evaluation length):
// by default 10 m along a 1-D profile (a record shorter than that has none), none for maps unless
// asked (then along the rows). A whole number of segments, so that each evaluation length holds
// the same segments whatever the rounding.
double evaluation_length_for(const AnalyzeCli& c, bool profile) {
  const bool given = c.evaluation_opt->count() > 0;
  const double L = c.evaluation_length;
  if (!given) return profile ? L : 0.0;
  if (!(std::isfinite(L) && L >= 0)) throw InputError("--evaluation-length", "must be a length >= 0 in m (0 switches it off)");
  if (L == 0) return 0.0;
  const double segments = L / c.mpd.baseline;
  if (!(segments >= 1 && segments <= 1e9) || std::abs(segments - std::round(segments)) > 1e-6 * segments) {
    char b[160];
    std::snprintf(b, sizeof b, "must be a whole number of MPD segments of %g m (--baseline), got %g m", c.mpd.baseline, L);
    throw InputError("--evaluation-length", b);
  }
  return L;
}

int run_analyze(const AnalyzeCli& c) {
  if (!(c.mpd.baseline > 0)) throw InputError("--baseline", "must be a positive length in m");
  if (!(c.mpd.lowpass_wavelength >= 0)) throw InputError("--lowpass", "must be >= 0 m (0 switches it off)");
  if (!(c.mpd.spike_alpha >= 0 && std::isfinite(c.mpd.spike_alpha)))
    throw InputError("--spike-alpha", "must be a finite slope >= 0 (0 switches spike removal off)");
  (void)evaluation_length_for(c, false);  // a bad --evaluation-length is refused before the file is read
  OutputSet outputs;
  outputs.input(c.input);
  const std::string json_path = outputs.add("--json", c.json), out_path = outputs.add("--out", c.out);
  PhaseTimer io;
  io.start("read");
  TextGridOptions text;
  if (c.dx_opt->count()) text.dx = c.dx;
  if (c.dy_opt->count()) text.dy = c.dy;
  text.unit_scale = unit_scale(c.unit, "--unit");
  text.periodic = c.periodic;
  text.points = c.points;
  if (c.max_gap_opt->count()) {
    if (!c.points) throw InputError("--max-gap", "applies to point clouds only (add --points)");
    text.max_gap = c.max_gap;
  }
  for (const CLI::Option* o : c.text_only)
    if (o->count() > 0) text.given.push_back(o->get_name());
  const LoadedSurface surface = load_surface(c.input, text);
  io.stop();
  print_load_warnings(surface);  // also under -q: they are about the data
  if (!c.quiet) {
    print_import(surface);
    std::printf("\n");
  }

  AnalysisOptions opt;
  opt.threads = c.threads;
  opt.mpd = c.mpd;
  // A 1-D profile is a continuous record (a laser profilometer's), a map a spot measurement.
  const bool continuous = c.mpd_method == "continuous" || (c.mpd_method == "auto" && surface.map.is_profile());
  opt.mpd.method = continuous ? MpdMethod::continuous : MpdMethod::spot;
  // Records of laser profilometers start and end on calibration plates; maps do not.
  opt.mpd.cut_plates = surface.map.is_profile() && !c.keep_plates;
  opt.expected_mpd = !c.no_expected_mpd;
  opt.mpd.evaluation_length = evaluation_length_for(c, surface.map.is_profile());
  AnalysisReport report = analyze_surface(surface, opt);

  PhaseTimer write;
  write.start("write");
  Provenance prov;
  prov.command = "analyze";
  prov.inputs = {{"surface", c.input}, {"format", surface.format}, {"read", describe_import(surface)}};
  prov.parameters = {{"baseline", c.mpd.baseline},
                     {"lowpass_wavelength", c.mpd.lowpass_wavelength},
                     {"highpass_wavelength", opt.mpd.method == MpdMethod::continuous ? c.mpd.highpass_wavelength : 0.0},
                     {"mpd_method", continuous ? "continuous" : "spot"},
                     {"resample", c.mpd.resample},
                     {"spike_alpha", c.mpd.spike_alpha},
                     {"cut_plates", opt.mpd.cut_plates},
                     {"evaluation_length", opt.mpd.evaluation_length},
                     {"expected_mpd", opt.expected_mpd}};
  if (c.points) prov.parameters["max_gap"] = c.max_gap_opt->count() ? nlohmann::json(c.max_gap) : nlohmann::json("auto");
  prov.model = "analysis";
  nlohmann::json timings = report.timer.to_json();
  timings["read"] = io.seconds("read");
  prov.timings = timings;
  nlohmann::json j = report.to_json();
  j["timings"]["read"] = io.seconds("read");
  j["provenance"] = prov.to_json();
  if (!c.json.empty()) write_text_atomically(json_path, j.dump(2) + "\n");
  if (!c.out.empty()) write_analysis_file(out_path, report, prov);
  outputs.commit();
  write.stop();

  if (!c.quiet) {
    std::printf("%s", format_analysis(report).c_str());
    std::printf("\ntimings\n  %-18s  %10.4f\n%s", "read", io.seconds("read"), report.timer.table().c_str());
    if (!c.json.empty() || !c.out.empty())
      std::printf("  %-18s  %10.4f\n", "write", write.seconds("write"));
  }
  return 0;
}

}  // namespace

Command add_analyze(CLI::App& root) {
  auto c = std::make_shared<AnalyzeCli>();
  CLI::App* s = root.add_subcommand("analyze", "texture statistics of a surface: PSD, moments, summits, MPD");
  s->footer(
      "Texture statistics of a surface: size and spacing; h0 (Sq), Sa, Ssk, Sku; rms slope (spectral\n"
      "sqrt(2 m2) and finite differences); m0, m2, m4, alpha; radially averaged PSD with a fit of\n"
      "plateau, roll-off q0 and Hurst exponent; summits against Nayak (eq. 3.69, 4.5); MPD after\n"
      "ISO 13473-1 over every row and column, ETD; Persson/BGT low-pressure kappa and Persson's\n"
      "A/A0. For a file made by `synth` the prescribed values stand beside the measured ones.\n"
      "Input: HDF5 (/height 2-D with dx, dy attributes in m, or /profile 1-D with dx); X3P (ISO\n"
      "25178-72: SUR maps, PRF profiles, data types I/L/F/D, checksums verified); a plain-text grid\n"
      "(whitespace/comma separated, rows = y; needs --dx); or with --points an x y z point cloud\n"
      "(one point per line), triangulated (CGAL Delaunay) and interpolated linearly onto a --dx grid,\n"
      "triangles longer than --max-gap left as dropouts. NaN or invalid points = dropouts.\n"
      "Example: wetroad analyze road.h5 --json road.json --out road-analysis.h5\n"
      "         wetroad analyze scan.xyz --points --unit mm --dx 2e-4");
  s->add_option("file", c->input, "surface file (HDF5, X3P, text grid or, with --points, a point cloud)")->type_name("FILE")->required();
  s->add_option("--json", c->json, "write the summary as JSON (SI units; keys in docs/file-formats.md)")->type_name("OUTPUT");
  s->add_option("--out", c->out, "write the summary, the radial PSD (/psd/q, /psd/C) and summit heights to HDF5")->type_name("OUTPUT");
  c->dx_opt = s->add_option("--dx", c->dx, "text grids: sample spacing along x in m; point clouds: the grid's (required for text)");
  c->dy_opt = s->add_option("--dy", c->dy, "text grids: spacing along y in m (default: --dx)");
  s->add_option("--unit", c->unit, "text grids: unit of the heights; point clouds: of x, y and z: m, mm, um, nm (default m)");
  s->add_flag("--points", c->points, "the text file holds x y z points (a point cloud; needs --dx, the grid spacing)");
  c->max_gap_opt = s->add_option("--max-gap", c->max_gap,
                                 "point clouds: triangles with a longer edge (m) are not interpolated but left as dropouts "
                                 "(default: 5 x the mean point spacing)");
  s->add_flag("--periodic", c->periodic, "text grids: the data wraps around (default: not periodic)");
  c->text_only = {c->dx_opt, c->dy_opt, s->get_option("--unit"), s->get_option("--points"), c->max_gap_opt,
                  s->get_option("--periodic")};
  s->add_option("--baseline", c->mpd.baseline, "MPD segment length in m (ISO 13473-1: 0.1)")->capture_default_str();
  s->add_option("--lowpass", c->mpd.lowpass_wavelength,
                "MPD low-pass cut-off wavelength in m, 0 = off (ISO 13473-1:2019 Annex D: 2.4e-3)")
      ->capture_default_str();
  s->add_option("--mpd-method", c->mpd_method,
                "MPD of a spot measurement (least-squares line removed per segment) or a continuous one "
                "(high-pass at 174.2 mm instead); auto: continuous for 1-D profiles, spot for maps")
      ->check(CLI::IsMember({"auto", "spot", "continuous"}))
      ->capture_default_str();
  s->add_option("--spike-alpha", c->mpd.spike_alpha,
                "MPD spikes (ISO 13473-1 Annex E): neighbours of the resampled profile differing by at least "
                "alpha x the spacing are both dropped and interpolated; 0 = off")
      ->capture_default_str();
  c->evaluation_opt =
      s->add_option("--evaluation-length", c->evaluation_length,
                    "MPD also per evaluation length in m along each profile (ISO 13473-1 continuous records, "
                    "e.g. 10 or 20): a whole number of segments; 0 = off (default: 10 for 1-D profiles, off for maps; "
                    "given for a map, along its rows)");
  s->add_flag("--keep-plates", c->keep_plates,
              "1-D profiles: keep flat runs at the record's ends that stand 2 mm or more off the road (calibration "
              "plates, cut by default; maps are never cut)");
  s->add_flag("!--no-resample", c->mpd.resample,
              "MPD on the raw sampling instead of the standard's 0.5 mm (1.0 mm) bin averages (not ISO)");
  s->add_flag("--no-expected-mpd", c->no_expected_mpd,
              "skip the MPD expected on 100 mm profiles from the prescribed PSD (synthesized files)");
  s->add_option("--threads", c->threads, "worker threads (default: all hardware threads); results do not depend on it")->check(CLI::NonNegativeNumber);
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_analyze(*c); }};
}

}  // namespace wr::app
