// `wetroad report`: the self-contained HTML report (reports/html_report.hpp).
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/commands.hpp"
#include "lib/core/errors.hpp"
#include "lib/friction/friction_file.hpp"
#include "lib/io/output_set.hpp"
#include "reports/sweep_outputs.hpp"
#include "reports/html_report.hpp"

namespace wr::app {
namespace {

struct ReportCli {
  std::vector<std::string> sweeps, friction;
  std::string measured, output, title = "wetroad report: wet friction";
  double ifi_a = 0, ifi_b = 0, ifi_c = 0, ifi_tx = 0;
  CLI::Option *ifi_a_opt = nullptr, *ifi_b_opt = nullptr, *ifi_c_opt = nullptr, *ifi_tx_opt = nullptr;
  bool quiet = false;
};

int run_report(const ReportCli& c) {
  // The F60 column needs both device constants; a lone one would be silently dropped.
  const bool a = c.ifi_a_opt->count() > 0, b = c.ifi_b_opt->count() > 0;
  if (a != b) throw InputError(a ? "--ifi-a" : "--ifi-b", "the IFI F60 needs both --ifi-a and --ifi-b");
  if (!b && (c.ifi_c_opt->count() > 0 || c.ifi_tx_opt->count() > 0))
    throw InputError("--ifi-c", "--ifi-c and --ifi-tx refine the F60 of --ifi-a and --ifi-b; give those too");
  if ((c.ifi_c_opt->count() > 0) != (c.ifi_tx_opt->count() > 0))
    throw InputError("--ifi-c", "--ifi-c and --ifi-tx go together (the ribbed-tyre term C Tx)");
  for (const auto& [opt, value] : {std::pair{c.ifi_a_opt, c.ifi_a}, {c.ifi_b_opt, c.ifi_b}, {c.ifi_c_opt, c.ifi_c}})
    if (opt->count() > 0 && !std::isfinite(value)) throw InputError(opt->get_name(), "must be a finite number");
  if (c.ifi_tx_opt->count() > 0 && !(c.ifi_tx >= 0 && c.ifi_tx <= 100))
    throw InputError("--ifi-tx", "the texture measure Tx must lie in 0 ... 100 mm");
  OutputSet outputs;
  for (const auto& s : c.sweeps) outputs.input(s);
  for (const auto& f : c.friction) outputs.input(f);
  outputs.input(c.measured);
  const std::string out_path = outputs.add("--output", c.output);
  ReportInput in;
  in.title = c.title;
  for (const auto& s : c.sweeps) in.sweeps.emplace_back(s, read_any_sweep_hdf5(s));
  for (const auto& f : c.friction) in.friction.emplace_back(f, read_friction_summary(f));
  if (!c.measured.empty()) {
    in.measured = read_measured_skid_csv(c.measured);
    in.measured_path = c.measured;
  }
  if (c.ifi_b_opt->count() > 0) in.ifi = IfiConstants{c.ifi_a, c.ifi_b, c.ifi_c, c.ifi_tx};
  try {
    write_html_report(out_path, in);
  } catch (const nlohmann::json::exception& e) {
    // A record edited or damaged after wetroad wrote it: a field missing or of the wrong type.
    std::string files;
    for (const auto& [file, j] : in.sweeps) files += (files.empty() ? "" : ", ") + file;
    for (const auto& [file, j] : in.friction) files += (files.empty() ? "" : ", ") + file;
    throw InputError(files, std::string("a field is missing or of the wrong type (") + e.what() +
                                "); not a record as wetroad writes it");
  }
  outputs.commit();
  if (!c.quiet)
    std::printf("wrote %s: %zu sweep(s), %zu friction result(s)%s; open it in any browser (self-contained, offline)\n",
                c.output.c_str(), in.sweeps.size(), in.friction.size(), in.measured.empty() ? "" : ", measured skid numbers");
  return 0;
}

}  // namespace

Command add_report(CLI::App& root) {
  auto c = std::make_shared<ReportCli>();
  CLI::App* s = root.add_subcommand("report", "write a self-contained HTML report of sweeps and skid numbers");
  s->footer(
      "One HTML file with the charts (gnuplot SVG, embedded), tables, the validity flags of every run and\n"
      "the source of every number (sweep file and run group). With --measured, the skid-number comparison:\n"
      "predicted SN40R against MPD from hysteresis sweeps (100 mu at 17.9 m/s, and by the IFI route), the\n"
      "elastostatic 100 mu of contact-model sweeps as its own series (not a skid number), the measured\n"
      "sites, the MPD of each peak, and the IFI speed constant Sp = 14.2 + 89.7 MPD per site (F60 too when\n"
      "the device constants are given). --friction adds the mu(v) curves of `wetroad friction --out`.\n"
      "Example: wetroad report --sweep sweep.h5 --friction mu.h5 --measured sites.csv -o report.html");
  s->add_option("--sweep", c->sweeps, "sweep result (sweep-coverage or sweep-roughness --out); repeatable")->type_name("FILE")
      ->check(CLI::ExistingFile);
  s->add_option("--friction", c->friction, "hysteresis friction result (wetroad friction --out): mu(v) dry/wet; repeatable")->type_name("FILE")
      ->check(CLI::ExistingFile);
  s->add_option("--measured", c->measured, "measured skid numbers: CSV site,mpd_mm,sn40r[,speed_kmh]")->type_name("FILE")
      ->check(CLI::ExistingFile);
  c->ifi_a_opt = s->add_option("--ifi-a", c->ifi_a, "IFI device constant A (F60 column; needs --ifi-b)");
  c->ifi_b_opt = s->add_option("--ifi-b", c->ifi_b, "IFI device constant B (with --ifi-a)");
  c->ifi_c_opt = s->add_option("--ifi-c", c->ifi_c, "IFI device constant C (ribbed tyre), with --ifi-tx");
  c->ifi_tx_opt = s->add_option("--ifi-tx", c->ifi_tx, "texture measure Tx for the C term, mm");
  s->add_option("--title", c->title, "report title")->capture_default_str();
  s->add_option("-o,--output", c->output, "the HTML file (written atomically)")->type_name("OUTPUT")->required();
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_report(*c); }};
}

}  // namespace wr::app
