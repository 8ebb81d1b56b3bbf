// `wetroad flow SURFACE`: the thin-film (Reynolds) flow through the gap of a contact on the map
// (lib/flow/thin_film_flow.hpp): the gap of the spectral half-space under a mean pressure, or of a
// rigid flat cutting the surface; its conductance tensor, flow factors and percolation.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/print_summary.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/flow/contact_gap.hpp"
#include "lib/flow/effective_medium.hpp"
#include "lib/flow/thin_film_flow.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "lib/io/vtu_writer.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "roads/surface_import.hpp"

namespace wr::app {
namespace {

struct FlowCli {
  std::string surface, json, vti, solver = "auto";
  double pressure = 0.3e6, young = 10e6, poisson = 0.45, contact_fraction = 0, separation = 0;
  double tolerance = 1e-10, contact_tol = 1e-8;
  bool rigid = false, quiet = false;
  int threads = 0;
  CLI::Option *pressure_opt = nullptr, *young_opt = nullptr, *nu_opt = nullptr, *fraction_opt = nullptr,
              *separation_opt = nullptr;
};

// Every option's value checked before any file is read or written.
void check_options(const FlowCli& c) {
  if (c.rigid) {
    for (const CLI::Option* o : {c.pressure_opt, c.young_opt, c.nu_opt})
      if (o->count()) throw InputError(o->get_name(), "is for the elastic contact; --rigid takes --contact-fraction or --separation");
    if (c.fraction_opt->count() == c.separation_opt->count())
      throw InputError("--rigid", "give exactly one of --contact-fraction F or --separation U");
    if (c.fraction_opt->count() && !(c.contact_fraction > 0 && c.contact_fraction < 1))
      throw InputError("--contact-fraction", "must be in (0, 1)");
    if (c.separation_opt->count() && !(c.separation > 0 && std::isfinite(c.separation)))
      throw InputError("--separation", "must be a length > 0 in m");
  } else {
    for (const CLI::Option* o : {c.fraction_opt, c.separation_opt})
      if (o->count()) throw InputError(o->get_name(), "is for a rigid flat: add --rigid");
    if (!(c.pressure > 0 && std::isfinite(c.pressure))) throw InputError("--pressure", "must be a mean pressure > 0 in Pa");
    if (!(c.young > 0 && std::isfinite(c.young))) throw InputError("--E", "must be a modulus > 0 in Pa");
    if (!(c.poisson >= 0 && c.poisson < 0.5)) throw InputError("--nu", "must be in [0, 0.5)");
    if (!(c.contact_tol > 0 && c.contact_tol < 1)) throw InputError("--contact-tol", "must be in (0, 1)");
  }
  if (!(c.tolerance > 0 && c.tolerance < 1)) throw InputError("--tol", "must be in (0, 1)");
}

// The contact state the flow runs on: the gap (m), the contact pressure (Pa; 0 for the rigid
// flat, whose load is not modelled) and what produced it.
struct ContactGap {
  HeightMap gap;
  std::vector<double> pressure;
  double mean_pressure = 0;  // Pa; NaN for the rigid flat
  double level = 0;          // m: the rigid flat's height above the mean plane
  std::string model;
  nlohmann::json record;
};

ContactGap elastic_gap(const FlowCli& c, const LoadedSurface& s) {
  const ElasticBody body{c.young, c.poisson};
  std::optional<SpectralNormalContact> solver;
  try {
    solver.emplace(s.map, body, c.threads, FftPlanning::measure);
  } catch (const std::invalid_argument& e) {
    throw InputError(s.source, e.what());
  }
  SpectralOptions opt;
  opt.tolerance = c.contact_tol;
  opt.threads = c.threads;
  const SpectralNormalResult r = solver->solve_load(c.pressure, opt);
  if (!r.converged) throw NumericalError("contact", "the spectral solver did not converge: " + r.message);
  ContactGap g{contact_gap_map(s.map, solver->pressure(), solver->gap()), {}, r.mean_pressure, 0,
               "spectral: elastic half-space, FFT boundary elements, Polonsky-Keer constrained CG (load control)", {}};
  g.pressure.assign(solver->pressure().begin(), solver->pressure().end());
  g.record = {{"iterations", r.iterations}, {"max_penetration", r.max_penetration}, {"contact_gap", r.contact_gap},
              {"e_star", body.e_star()}, {"wall_s", r.wall_s}};
  return g;
}

ContactGap rigid_gap(const FlowCli& c, const LoadedSurface& s) {
  const double level = c.fraction_opt->count() ? level_at_contact_fraction(s.map, c.contact_fraction)
                                               : level_at_mean_separation(s.map, c.separation);
  ContactGap g{rigid_flat_gap(s.map, level), std::vector<double>(s.map.size(), 0.0), std::nan(""), level,
               "rigid flat cutting the surface (bearing area: no elastic deformation)", {}};
  g.record = {{"level", level}};
  return g;
}

// The mean-field rung beside the map's answer (lib/flow/effective_medium.hpp): Bruggeman's medium
// from the contact fraction, the mean gap and the surface's rms height, against the mean of the
// map's kxx and kyy. Within a factor of 2 the cheap rung answers the scene's questions (the
// squeeze-out's times scale with 1/K).
struct MeanField {
  double k = 0, ratio = 0, critical_contact = 0, rms = 0;
  bool suffices = false;
};

MeanField mean_field(const HeightMap& surface, const FlowConductance& k, double area, bool rigid) {
  MeanField m;
  double mean = 0, sq = 0;
  for (double h : surface.h) mean += h;
  mean /= static_cast<double>(surface.size());
  for (double h : surface.h) sq += (h - mean) * (h - mean);
  m.rms = std::sqrt(sq / static_cast<double>(surface.size()));
  m.critical_contact = rigid ? kRigidPercolationContact : kElasticPercolationContact;
  m.k = effective_medium_conductance({area, k.mean_gap, m.rms}, m.critical_contact);
  const double map = 0.5 * (k.kxx + k.kyy);
  m.ratio = map > 0 ? m.k / map : INFINITY;
  m.suffices = m.ratio >= 0.5 && m.ratio <= 2;
  return m;
}

nlohmann::json flow_json(const FlowConductance& k, const ContactGap& g, double area) {
  const double u = k.mean_gap, plates = u * u * u / 12;
  auto ratio = [&](double v) { return plates > 0 ? nlohmann::json(v / plates) : nlohmann::json(nullptr); };
  return {{"mean_pressure", std::isnan(g.mean_pressure) ? nlohmann::json(nullptr) : nlohmann::json(g.mean_pressure)},
          {"area_fraction", area},
          {"free_fraction", k.free_fraction},
          {"mean_gap", k.mean_gap},
          {"conductance", {{"kxx", k.kxx}, {"kxy", k.kxy}, {"kyx", k.kyx}, {"kyy", k.kyy}}},
          {"flow_factor", {{"xx", ratio(k.kxx)}, {"xy", ratio(k.kxy)}, {"yx", ratio(k.kyx)}, {"yy", ratio(k.kyy)}}},
          {"percolates_x", k.percolates_x},
          {"percolates_y", k.percolates_y},
          {"solver", k.solver},
          {"iterations", k.iterations},
          {"residual", k.residual},
          {"unknowns", k.unknowns},
          {"contact", g.record}};
}

void write_vti(const std::string& path, const ContactGap& g, const FlowField& f) {
  std::vector<double> gap(g.gap.h.begin(), g.gap.h.end()), contact(g.gap.size());
  for (std::size_t k = 0; k < contact.size(); ++k) contact[k] = g.gap.h[k] == 0 ? 1.0 : 0.0;
  write_vti_file(path, g.gap.nx, g.gap.ny, g.gap.dx, g.gap.dy,
                 {{"gap", &gap}, {"contact_pressure", &g.pressure}, {"contact", &contact},
                  {"flow_pressure", &f.pressure}, {"flux_x", &f.flux_x}, {"flux_y", &f.flux_y}});
}

void print_result(const FlowCli& c, const LoadedSurface& s, const ContactGap& g, const FlowConductance& k, double area,
                  const nlohmann::json& timings) {
  std::printf("%s: %zux%zu map, dx %.4g m; %s\n", s.source.c_str(), s.map.nx, s.map.ny, s.map.dx, g.model.c_str());
  if (c.rigid)
    std::printf("  flat level       %.4e m above the mean plane\n", g.level);
  else
    std::printf("  pressure         %.4e Pa (E %.4g Pa, nu %.3g)\n", g.mean_pressure, c.young, c.poisson);
  const double u = k.mean_gap, plates = u * u * u / 12;
  std::printf("  A/A0             %.4f\n  mean gap         %.4e m\n", area, u);
  std::printf("  K (m^3)          [%.4e %.4e; %.4e %.4e]\n", k.kxx, k.kxy, k.kyx, k.kyy);
  if (plates > 0)
    std::printf("  K / (u^3/12)     [%.4f %.4f; %.4f %.4f]  (parallel plates at the mean gap u: identity)\n",
                k.kxx / plates, k.kxy / plates, k.kyx / plates, k.kyy / plates);
  std::printf("  free area        %.4f, percolates in x: %s, in y: %s\n", k.free_fraction, k.percolates_x ? "yes" : "no",
              k.percolates_y ? "yes" : "no");
  std::printf("  solver           %s, %zu unknowns, %d iterations, relative residual %.2e, %.3f s\n", k.solver.c_str(),
              k.unknowns, k.iterations, k.residual, k.wall_s);
  std::printf("  timing [s]:");
  for (const char* phase : {"load", "contact", "flow", "write", "total"}) std::printf("  %s %.3f", phase, timings[phase].get<double>());
  std::printf("\n");
}

int run_flow(const FlowCli& c) {
  const auto t0 = std::chrono::steady_clock::now();
  check_options(c);
  const FlowSolver solver = parse_flow_solver(c.solver, "--solver");
  OutputSet outputs;
  outputs.input(c.surface);
  const std::string json_path = outputs.add("--json", c.json), vti_path = outputs.add("--vti", c.vti);
  const LoadedSurface s = load_surface(c.surface);
  require_periodic_map(s, "the flow model repeats the surface");
  print_load_warnings(s);
  nlohmann::json timings = nlohmann::json::object();
  timings["load"] = seconds_since(t0);
  auto t = std::chrono::steady_clock::now();
  const ContactGap g = c.rigid ? rigid_gap(c, s) : elastic_gap(c, s);
  timings["contact"] = seconds_since(t);
  // PETSc (and MPI) only for the amg solver: the direct solver keeps the command a plain program.
  int argc = 1;
  char name[] = "wetroad";
  char* args[] = {name, nullptr};
  char** argv = args;
  std::optional<PetscSession> petsc;
  if (solver == FlowSolver::amg) petsc.emplace(&argc, &argv);
  FlowOptions fo;
  fo.solver = solver;
  fo.tolerance = c.tolerance;
  fo.threads = c.threads;
  FlowField field;
  t = std::chrono::steady_clock::now();
  const FlowConductance k = thin_film_conductance(g.gap, fo, c.vti.empty() ? nullptr : &field);
  timings["flow"] = seconds_since(t);
  const double area = contact_fraction(g.gap);
  // No flow path in either direction: the conductance the command exists for is zero, and the
  // film the tread presses stays in closed pools. Refused like any question without an answer.
  if (!k.percolates_x && !k.percolates_y) {
    char why[200];
    std::snprintf(why, sizeof why,
                  "no drainage in any direction: the free area percolates in neither x nor y at A/A0 = %.3f (the water "
                  "stays in closed pools, K = 0); give a lower %s",
                  area, c.rigid ? "--contact-fraction or a larger --separation" : "--pressure");
    throw InputError(c.surface, why);
  }
  const MeanField mf = mean_field(s.map, k, area, c.rigid);
  t = std::chrono::steady_clock::now();
  if (!vti_path.empty()) write_vti(vti_path, g, field);
  Provenance prov;
  prov.command = "flow";
  prov.inputs = {{"surface", c.surface}};
  prov.parameters = {{"rigid", c.rigid}, {"solver", c.solver}, {"tolerance", c.tolerance}};
  if (c.rigid) {
    if (c.fraction_opt->count()) prov.parameters["contact_fraction"] = c.contact_fraction;
    if (c.separation_opt->count()) prov.parameters["separation"] = c.separation;
  } else {
    prov.parameters.update({{"pressure", c.pressure}, {"E", c.young}, {"nu", c.poisson}, {"contact_tol", c.contact_tol}});
  }
  prov.model = "thin-film flow: steady Reynolds equation on the periodic map, cell-centred finite volumes, harmonic face "
               "conductances g^3/12 (Patir & Cheng 1978; Dapp et al. PRL 108, 244301 (2012)); gap from the " + g.model;
  timings["write"] = seconds_since(t);
  timings["total"] = seconds_since(t0);
  prov.timings = timings;
  nlohmann::json j = flow_json(k, g, area);
  j["effective_medium"] = {{"conductance", mf.k}, {"ratio_to_map", mf.ratio}, {"critical_contact", mf.critical_contact},
                           {"rms_height", mf.rms}, {"suffices", mf.suffices}};
  j["provenance"] = prov.to_json();
  if (!json_path.empty()) write_text_atomically(json_path, j.dump(2) + "\n");
  outputs.commit();
  if (!c.quiet) {
    print_result(c, s, g, k, area, timings);
    std::printf("  mean field       K %.4e m^3 (Bruggeman effective medium from A/A0, the mean gap and the map's rms %.3e m,\n"
                "                   threshold A_c %.2f): %.2f x the map's; %s\n",
                mf.k, mf.rms, mf.critical_contact, mf.ratio,
                mf.suffices ? "within a factor 2, the mean-field rung suffices for this scene"
                            : "off by more than a factor 2: this scene needs the map's flow");
  }
  return 0;
}

}  // namespace

Command add_flow(CLI::App& root) {
  auto c = std::make_shared<FlowCli>();
  CLI::App* s = root.add_subcommand("flow", "thin-film (Reynolds) flow of water through the gap of a contact on the map");
  s->footer(
      "Water squeezed between tread and road flows through the gap g(x, y) of their contact. In the thin-film\n"
      "limit the pressure obeys div(g^3/(12 eta) grad p) = 0 (Reynolds); on the periodic map, for a mean\n"
      "pressure gradient G, the mean flux per unit width is J = -(K/eta) G with the conductance tensor K (m^3;\n"
      "g^3/12 for parallel plates: K/(u^3/12) is Patir & Cheng's pressure flow factor at the mean gap u).\n"
      "Gap: the elastic half-space (spectral model) under --pressure, or with --rigid a rigid flat cutting the\n"
      "surface at --contact-fraction or --separation. Contact closes the gap: when the contact patches join\n"
      "across the map (A/A0 about 0.42 elastic, Dapp et al. PRL 108, 244301 (2012)) the free area stops\n"
      "percolating and K vanishes in that direction. Cell-centred finite volumes, harmonic face means;\n"
      "CHOLMOD (direct) or CG + GAMG (PETSc). --vti writes gap, contact pressure, contact and the flow of a\n"
      "unit gradient in x for ParaView.\n"
      "Example: wetroad flow road.h5 --pressure 3e5 --json flow.json --vti flow.vti\n"
      "         wetroad flow road.h5 --rigid --contact-fraction 0.3");
  s->add_option("surface", c->surface, "the road surface (periodic HDF5 map or text grid)")->type_name("FILE")->required();
  c->pressure_opt = s->add_option("--pressure", c->pressure, "mean contact pressure, Pa (elastic)")->capture_default_str();
  c->young_opt = s->add_option("--E,--young", c->young, "Young's modulus of the rubber, Pa (elastic)")->capture_default_str();
  c->nu_opt = s->add_option("--nu", c->poisson, "Poisson's ratio of the rubber (elastic)")->capture_default_str();
  s->add_option("--contact-tol", c->contact_tol, "the spectral contact solver's tolerance (relative l1 pressure change)")
      ->capture_default_str();
  s->add_flag("--rigid", c->rigid, "a rigid flat cutting the surface instead of the elastic contact");
  c->fraction_opt = s->add_option("--contact-fraction", c->contact_fraction, "--rigid: the flat's level where A/A0 = F");
  c->separation_opt = s->add_option("--separation", c->separation, "--rigid: the flat's level where the mean gap = U, m");
  s->add_option("--solver", c->solver, "auto (cholmod: measured faster at every size, docs/performance.md), cholmod, or amg")
      ->capture_default_str();
  s->add_option("--tol", c->tolerance, "amg: relative residual of the CG solves")->capture_default_str();
  s->add_option("--threads", c->threads, "FFT threads of the contact solver (default: all cores)")->check(CLI::NonNegativeNumber);
  s->add_option("--json", c->json, "write the result as JSON (SI units)")->type_name("OUTPUT");
  s->add_option("--vti", c->vti, "write gap, contact and flow fields as VTK image data (.vti)")->type_name("OUTPUT");
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  return {s, [c] { return run_flow(*c); }};
}

}  // namespace wr::app
