// `wetroad compound DMA.csv -o compound.json`: a rubber's compound file from its lab data (DMA
// frequency sweeps at several temperatures) by time-temperature superposition
// (lib/friction/master_curve.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/friction/dma_data.hpp"
#include "lib/friction/master_curve.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "reports/plot.hpp"
#include "wetroad/version.hpp"

namespace wr::app {
namespace {

struct CompoundCli {
  std::string input, out, json, plots, law = "wlf", name;
  double reference = 0, poisson = 0.5;
  bool vertical = false, quiet = false;
  CLI::Option* reference_opt = nullptr;
};

ShiftLaw parse_law(const std::string& s) {
  if (s == "wlf" || s == "vft") return ShiftLaw::wlf;  // VFT is WLF rewritten (Ferry, eq. 11-33)
  if (s == "arrhenius") return ShiftLaw::arrhenius;
  throw InputError("--shift-law", "\"" + s + "\" is not wlf, vft or arrhenius");
}

nlohmann::json dma_json(const MasterCurve& m, const DmaData& d, const CompoundCli& c) {
  nlohmann::json rows = nlohmann::json::array();
  for (const ShiftRow& r : m.shifts)
    rows.push_back({{"temperature_c", r.temperature}, {"log10_at", r.log_at}, {"log10_at_fit", r.log_at_fit},
                    {"mismatch_decades", r.mismatch}});
  nlohmann::json j = {{"file", c.input},
                      {"points", d.points},
                      {"isotherms", d.isotherms.size()},
                      {"moduli", d.shear ? "shear (G', G''), E = 2 (1 + nu) G" : "Young's (E', E'')"},
                      {"vertical_shift", c.vertical},
                      {"shift_law", m.law == ShiftLaw::wlf ? "wlf" : "arrhenius"},
                      {"shift_fit_rms_decades", m.fit_rms},
                      {"shifts", rows},
                      {"master_curve_rows", m.table.omega.size()},
                      {"prony_terms", m.prony.terms.size()},
                      {"prony_max_misfit", m.prony.max_misfit},
                      {"prony_rms_misfit", m.prony.rms_misfit},
                      {"loss_peak_rad_s", m.loss_peak_omega},
                      {"loss_peak_tan_delta", m.loss_peak_tan_delta},
                      {"glass_transition_c", m.glass_transition ? nlohmann::json(*m.glass_transition) : nlohmann::json(nullptr)}};
  if (d.strain_max > 0) j["strain_amplitude"] = {d.strain_min, d.strain_max};
  return j;
}

void write_plots(const std::string& dir, const MasterCurve& m, const DmaData& d, const Compound& fit) {
  const std::string t = " (T_ref " + std::to_string(static_cast<int>(std::lround(m.reference_temperature))) + " C)";
  PlotSpec e1{"storage modulus master curve" + t, "reduced frequency omega aT [rad/s]", "E\u2032 [Pa]", true, true, {}};
  PlotSpec e2{"loss modulus master curve" + t, "reduced frequency omega aT [rad/s]", "E\u2033 [Pa]", true, true, {}};
  PlotSpec td{"tan delta master curve" + t, "reduced frequency omega aT [rad/s]", "tan delta", true, true, {}};
  for (std::size_t i = 0; i < d.isotherms.size(); ++i) {
    const Isotherm& iso = d.isotherms[i];
    const double shift = std::pow(10.0, m.shifts[i].log_at);
    const std::string label = std::to_string(static_cast<int>(std::lround(iso.temperature))) + " C";
    PlotSeries s1{label, {}, {}, "points", {}}, s2 = s1, s3 = s1;
    for (std::size_t k = 0; k < iso.omega.size(); ++k) {
      s1.x.push_back(iso.omega[k] * shift), s1.y.push_back(iso.storage[k]);
      s2.x.push_back(iso.omega[k] * shift), s2.y.push_back(iso.loss[k]);
      s3.x.push_back(iso.omega[k] * shift), s3.y.push_back(iso.loss[k] / iso.storage[k]);
    }
    e1.series.push_back(s1), e2.series.push_back(s2), td.series.push_back(s3);
  }
  PlotSeries f1{"causal Prony fit", {}, {}, "lines", {}}, f2 = f1, f3 = f1;
  for (double w : m.table.omega) {
    const std::complex<double> e = fit.modulus_at_reference(w);
    f1.x.push_back(w), f1.y.push_back(e.real());
    f2.x.push_back(w), f2.y.push_back(e.imag());
    f3.x.push_back(w), f3.y.push_back(e.imag() / e.real());
  }
  e1.series.push_back(f1), e2.series.push_back(f2), td.series.push_back(f3);
  e1.key = e2.key = td.key = "outside right";  // a legend of many isotherms would hide the curve
  write_svg_plot(dir + "/master-storage.svg", e1);
  write_svg_plot(dir + "/master-loss.svg", e2);
  write_svg_plot(dir + "/master-tan-delta.svg", td);
  PlotSpec sh{"shift factors" + t, "temperature [C]", "log10 aT", false, false, {}};
  PlotSeries meas{"by overlap of adjacent isotherms", {}, {}, "points", {}}, law{m.law == ShiftLaw::wlf ? "WLF fit" : "Arrhenius fit", {}, {}, "lines", {}};
  for (const ShiftRow& r : m.shifts) meas.x.push_back(r.temperature), meas.y.push_back(r.log_at);
  const double a = m.shifts.front().temperature, b = m.shifts.back().temperature;
  for (int k = 0; k <= 50; ++k) law.x.push_back(a + (b - a) * k / 50), law.y.push_back(m.log10_shift(law.x.back()));
  sh.series = {meas, law};
  write_svg_plot(dir + "/shift-factors.svg", sh);
}

void print_master(const MasterCurve& m, const DmaData& d, const Compound& c) {
  std::printf("%s: %zu points in %zu isotherms, %.1f ... %.1f C, %s\n", d.source.c_str(), d.points, d.isotherms.size(),
              d.isotherms.front().temperature, d.isotherms.back().temperature,
              d.shear ? "shear moduli (E = 2 (1 + nu) G)" : "Young's moduli");
  std::printf("  %9s %12s %12s %14s\n", "T (C)", "log10 aT", "law", "mismatch (dec)");
  for (const ShiftRow& r : m.shifts) std::printf("  %9.2f %12.4f %12.4f %14.4f\n", r.temperature, r.log_at, r.log_at_fit, r.mismatch);
  if (m.law == ShiftLaw::wlf)
    std::printf("  WLF at T_ref %.2f C: C1 %.4g, C2 %.4g K (rms of log aT %.3g decades)\n", m.reference_temperature, m.c1, m.c2, m.fit_rms);
  else
    std::printf("  Arrhenius at T_ref %.2f C: Ea %.4g kJ/mol (rms of log aT %.3g decades)\n", m.reference_temperature,
                1e-3 * m.activation_energy, m.fit_rms);
  std::printf("  master curve: %zu rows over %.3g ... %.3g rad/s; causal Prony fit: %zu terms, misfit max %.2f %%, rms %.2f %%\n",
              m.table.omega.size(), m.table.omega.front(), m.table.omega.back(), c.terms.size(), 100 * m.prony.max_misfit,
              100 * m.prony.rms_misfit);
  std::printf("  rubbery E %.4g Pa, glassy E %.4g Pa; loss peak at %.3g rad/s (T_ref), tan delta %.3g\n", c.e_relaxed,
              c.glassy_modulus(), m.loss_peak_omega, m.loss_peak_tan_delta);
  if (m.glass_transition)
    std::printf("  glass transition (E'' peak at 1 Hz): %.1f C\n", *m.glass_transition);
  else
    std::printf("  glass transition: outside the shift law's range\n");
}

int run_compound(const CompoundCli& c) {
  const ShiftLaw law = parse_law(c.law);
  OutputSet outputs;
  outputs.input(c.input);
  const std::string out_path = outputs.add("-o", c.out), json_path = outputs.add("--json", c.json),
                    plots_dir = outputs.add_directory("--plots", c.plots);
  const DmaData d = read_dma_csv(c.input, c.poisson);
  MasterCurveOptions opt;
  opt.law = law;
  opt.vertical_shift = c.vertical;
  if (c.reference_opt->count()) opt.reference_temperature = c.reference;
  const MasterCurve m = build_master_curve(d, opt);
  const std::string name = c.name.empty() ? std::filesystem::path(c.input).stem().string() : c.name;
  const Compound compound = compound_from_master(m, name, "DMA data " + c.input + " (wetroad compound, " + kVersion + ")", c.poisson);
  nlohmann::json j = compound_to_json(compound);
  j["dma"] = dma_json(m, d, c);
  Provenance prov;
  prov.command = "compound";
  prov.inputs = {{"dma", c.input}};
  prov.parameters = {{"shift_law", c.law}, {"vertical_shift", c.vertical}, {"poisson", c.poisson},
                     {"reference_temperature", m.reference_temperature}};
  prov.model = "time-temperature superposition by overlap of adjacent isotherms, least-squares shift law, causal Prony fit";
  j["provenance"] = prov.to_json();
  write_text_atomically(out_path, j.dump(2) + "\n");
  if (!json_path.empty()) write_text_atomically(json_path, j["dma"].dump(2) + "\n");
  if (!plots_dir.empty()) write_plots(plots_dir, m, d, compound);
  outputs.commit();
  if (!c.quiet) {
    print_master(m, d, compound);
    std::printf("wrote %s (use it with --compound)\n", c.out.c_str());
  }
  return 0;
}

}  // namespace

Command add_compound(CLI::App& root) {
  auto c = std::make_shared<CompoundCli>();
  CLI::App* s = root.add_subcommand("compound", "a rubber compound from DMA lab data (time-temperature superposition)");
  s->footer(
      "DMA frequency sweeps at several temperatures (CSV with named columns and units: temperature [C|K|F],\n"
      "frequency [Hz|rad/s], E' and E'' or G' and G'' [Pa|kPa|MPa|GPa], optional strain [-|%]; docs/file-formats.md)\n"
      "-> horizontal shift factors by overlap of adjacent isotherms (optionally a vertical T0/T shift), a WLF or\n"
      "Arrhenius law fitted to them, the master curve at the reference temperature and its causal Prony series\n"
      "(Kramers-Kronig checked), written as a compound file for --compound, with the shift table, the fits'\n"
      "residuals, the loss peak and the glass transition (E'' peak at 1 Hz). Charts: master curves of E', E'',\n"
      "tan delta with the isotherms in their colours, and log aT against temperature.\n"
      "Example: wetroad compound tread-dma.csv -o tread.json --plots tread-charts\n"
      "         wetroad friction road.h5 --compound tread.json");
  s->add_option("dma", c->input, "DMA data (CSV)")->type_name("FILE")->required();
  s->add_option("-o,--out", c->out, "the compound file to write (JSON)")->type_name("OUTPUT")->required();
  c->reference_opt = s->add_option("--reference-temperature", c->reference,
                                   "reference temperature of the master curve, deg C (default: the isotherm nearest 20 C)");
  s->add_option("--shift-law", c->law, "wlf (= vft) or arrhenius")->capture_default_str();
  s->add_flag("--vertical-shift", c->vertical, "multiply the moduli by T0/T (absolute) before shifting");
  s->add_option("--poisson", c->poisson, "Poisson's ratio (the compound's; E = 2 (1 + nu) G for shear data)")->capture_default_str();
  s->add_option("--name", c->name, "the compound's name (default: the file's stem)");
  s->add_option("--json", c->json, "write the superposition's details (shift table, residuals) as JSON")->type_name("OUTPUT");
  s->add_option("--plots", c->plots, "folder for the charts (SVG)")->type_name("FOLDER");
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_compound(*c); }};
}

}  // namespace wr::app
