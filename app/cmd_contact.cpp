// `wetroad contact`: normal load and shear test of an elastic block on a (wet) road surface
// (lib/fem/block_press_shear.hpp). Runs under mpirun; rank 0 prints and writes.
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <chrono>
#include <limits>
#include <memory>

#include "app/commands.hpp"
#include "app/contact_output.hpp"
#include "app/launch.hpp"
#include "app/print_summary.hpp"
#include "app/scene_options.hpp"
#include "lib/analytic/area_load_fit.hpp"
#include "lib/analytic/contact_theory.hpp"
#include "lib/scene/contact_scene.hpp"
#include "lib/contact/friction_convergence.hpp"
#include "lib/contact/model_ladder.hpp"
#include "lib/contact/periodic_obstacle.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/provenance.hpp"
#include "lib/fem/block_press_shear.hpp"
#include "lib/fem/petsc_session.hpp"
#include "lib/core/fft.hpp"
#include "lib/spectral/spectral_press_shear.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/hdf5_file.hpp"
#include "lib/io/output_set.hpp"
#include "roads/height_stats.hpp"
#include "roads/surface_import.hpp"
#include "water/water_file.hpp"

namespace wr::app {
namespace {

struct ContactCli {
  std::string surface, wet, problem = "normal", json, petsc, model = "fem", out, vtu, checkpoint, restart;
  SceneCli sc;  // every scene option (app/scene_options.hpp); `contact`'s defaults set in add_contact
  bool quiet = false, trace = false;
  // Where --json and --out are written (OutputSet staging paths; committed together).
  std::string json_stage, out_stage;
};

// --json and --out (contact-face maps per step), each written atomically.
void write_contact_files(const ContactCli& c, const nlohmann::json& summary, const std::vector<ContactStep>& steps,
                         std::size_t face_nx, std::size_t face_ny, double face_spacing, const Provenance& prov) {
  if (!c.json.empty()) write_text_atomically(c.json_stage, summary.dump(2) + "\n");
  if (c.out.empty()) return;
  Hdf5Writer w(c.out_stage);
  w.create_group("/steps");
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const ContactStep& st = steps[k];
    const std::string g = "/steps/" + std::to_string(k + 1);
    w.create_group(g);
    w.write_matrix(g + "/pressure", st.face_pressure.data(), face_ny, face_nx);
    w.write_matrix(g + "/gap", st.face_gap.data(), face_ny, face_nx);
    w.write_matrix(g + "/status", st.face_status.data(), face_ny, face_nx);
    w.write_attr(g, "summary", contact_step_json(st).dump());
  }
  w.write_attr("/", "face_spacing", face_spacing);
  w.write_attr("/", "summary", summary.dump());
  w.write_attr("/", "provenance", prov.to_json().dump());
  w.commit();
}

// The failed step's reason and residual history on stderr; exit code 3.
int report_failure(const ContactCli& c, const std::vector<ContactStep>& steps, const char* measure) {
  const ContactStep& last = steps.back();
  std::fprintf(stderr, "wetroad: error: contact step %zu did not converge: %s\n", steps.size(), last.message.c_str());
  std::fprintf(stderr, "  %s:", measure);
  // The last iterations tell how it failed; a long history would flood the terminal.
  constexpr std::size_t kShown = 12;
  const std::size_t from = last.history.size() > kShown ? last.history.size() - kShown : 0;
  if (from > 0) std::fprintf(stderr, " (%zu earlier) ...", from);
  for (std::size_t i = from; i < last.history.size(); ++i) std::fprintf(stderr, " %.2e", last.history[i]);
  std::fprintf(stderr, "\n  the %zu finished steps are kept%s\n", steps.size() - 1,
               c.json.empty() ? "" : (" in " + c.json + " (status \"failed\")").c_str());
  return 3;
}

// The model that runs, its validity checks, and the same as JSON for every output.
struct Validity {
  ContactModel model;
  std::vector<ValidityCheck> checks;
  nlohmann::json json;
};

// A result outside its model's validity is said so on stderr (and flagged in --json/--out).
void warn_if_invalid(ContactModel m, const std::vector<ValidityCheck>& checks) {
  for (const auto& v : checks)
    if (!v.passed)
      std::fprintf(stderr, "wetroad: warning: outside the %s model's validity (%s): %s\n", model_name(m), v.name.c_str(),
                   v.detail.c_str());
}

// The contact scene the options describe, for `model`: what check_contact_scene validates for
// every model, and what the models run.
ContactScene scene_of(const ContactCli& c, ContactModel model) {
  ContactScene scene = c.sc.scene;
  scene.model = model;
  scene.shear = c.problem == "shear";
  return scene;
}

// The analytic model: Persson's contact area (erf form, eq. 3.162 / 5.3) at each mean pressure.
int run_analytic(const ContactCli& c, const LoadedSurface& s, const ContactRequest& req, const Validity& validity,
                 OutputSet& outputs) {
  const ContactScene& sc = c.sc.scene;
  if (!(sc.pressure > 0)) throw InputError("--pressure", "the analytic model needs a mean pressure, Pa");
  if (!c.out.empty()) throw InputError("--out", "the analytic model has no contact maps");
  if (!(req.rms_slope > 0 && std::isfinite(req.rms_slope)))
    throw InputError(s.source, "is flat (rms slope 0): the analytic model's sigma* = sigma0 / (E* rms slope) has no value; "
                               "a flat surface is in full contact at any load");
  warn_if_invalid(validity.model, validity.checks);
  const auto t0 = std::chrono::steady_clock::now();
  const double a0 = s.map.lx() * s.map.ly();
  const bool talk = !c.quiet;
  if (talk) {
    std::printf("%s: %zux%zu obstacle, rms slope %.4g; analytic model (Persson, erf form; BGT slope %.3f beside it)\n",
                s.source.c_str(), s.map.nx, s.map.ny, req.rms_slope, kappa_bgt());
    print_step_header();
  }
  nlohmann::json rows = nlohmann::json::array();
  const std::vector<ContactStep> steps = analytic_normal_curve(scene_of(c, ContactModel::analytic), req.rms_slope, a0);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const ContactStep& st = steps[k];
    if (talk) print_step_row(int(k) + 1, st);
    nlohmann::json row = contact_step_json(st);
    row["area_fraction_bgt"] = kappa_bgt() * st.sigma_star;
    rows.push_back(row);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Provenance prov;
  prov.command = "contact";
  prov.inputs = {{"surface", c.surface}, {"wet", c.wet}};
  prov.parameters = {{"problem", c.problem}, {"pressure", sc.pressure}, {"steps", sc.normal_steps}, {"E", sc.young},
                     {"nu", sc.poisson}};
  prov.model = "analytic: Persson A/A0 = erf(sqrt(2) sigma*) (thesis eq. 3.162, 5.3); BGT kappa sigma* beside it";
  prov.timings = {{"total", wall}};
  nlohmann::json j = {{"model", "analytic"}, {"rms_slope", req.rms_slope}, {"e_star", req.e_star},
                      {"kappa_persson", kappa_persson()}, {"kappa_bgt", kappa_bgt()}, {"wall_s", wall},
                      {"status", "ok"}, {"steps", rows}, {"validity", validity.json}, {"provenance", prov.to_json()}};
  // The thesis's fits of the same curve (eq. 5.4 quartic, eq. 3.179 YAM): the parameters a
  // Persson curve maps to, comparable with those of the FEM and spectral runs.
  j["area_load_fit"] = area_load_fit_json(steps, talk);
  if (!c.json.empty()) write_text_atomically(c.json_stage, j.dump(2) + "\n");
  outputs.commit();
  return 0;
}

// The spectral model (lib/spectral/): a periodic layer (or half-space) instead of the block.
int run_spectral(const ContactCli& c, const LoadedSurface& surface, const Validity& validity, OutputSet& outputs) {
  const ContactScene& sc = c.sc.scene;
  if (sc.refine < 1 || sc.refine > 16) throw InputError("--refine", "must be 1 ... 16");
  ContactScene scene = scene_of(c, ContactModel::spectral);
  scene.planning = FftPlanning::measure;  // one run: the machine's fastest plans
  const bool talk = !c.quiet;
  SceneRunHooks hooks;
  hooks.face_maps = !c.out.empty();
  // The face lattice of the FEM (obstacle spacing / refine) on the same triangulated obstacle;
  // called once the model's options passed their checks.
  hooks.on_setup = [&](const SceneSetup& g) {
    warn_if_invalid(validity.model, validity.checks);
    if (!talk) return;
    const bool half_space = std::isinf(g.thickness);
    std::printf("%s: %zux%zu obstacle, dx %.4g m, rms slope %.4g; spectral model, %s\n", surface.source.c_str(), g.nx,
                g.ny, g.dx, g.rms_slope, half_space ? "half-space" : "layer with its far face fixed");
    if (!half_space) std::printf("  layer thickness %.4g m\n", g.thickness);
    print_step_header();
  };
  int k = 0;
  hooks.on_step = [&](const ContactStep& st) {
    if (talk) print_step_row(++k, st);
  };
  const SceneResult run = run_contact_scene(surface.map, scene, MPI_COMM_SELF, hooks);
  const SpectralTestResult& r = *run.spectral;
  const SpectralTestOptions& o = *run.spectral_options;
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& st : r.steps) steps.push_back(contact_step_json(st));
  Provenance prov;
  prov.command = "contact";
  prov.inputs = {{"surface", c.surface}, {"wet", c.wet}};
  prov.parameters = {{"problem", c.problem}, {"uz", sc.uz}, {"ux", sc.ux}, {"pressure", sc.pressure},
                     {"steps", sc.normal_steps}, {"shear_steps", o.shear_steps}, {"damping", o.damping},
                     {"geometry_tolerance", o.geometry_tolerance},
                     {"E", sc.young}, {"nu", sc.poisson},
                     {"thickness", o.body.half_space() ? nlohmann::json("inf") : nlohmann::json(o.body.thickness)},
                     {"tolerance", o.solver.tolerance},
                     {"cg_precision", o.solver.single_precision_cg() ? "single" : "double"}, {"threads", sc.threads}};
  prov.model = "spectral: FFT boundary elements, periodic elastic " +
               std::string(o.body.half_space() ? "half-space" : "layer with a fixed far face") +
               ", Polonsky-Keer constrained CG (FFT-preconditioned)" +
               (o.shear ? "; shear: frictionless tractions along the obstacle normal, Boussinesq-Cerruti coupling, "
                          "geometry-following iteration"
                        : "");
  double t_sol = 0;
  for (const auto& st : r.steps) t_sol += st.wall_s;
  prov.timings = {{"setup", r.wall_setup}, {"solve", t_sol}, {"total", r.wall_s}};
  nlohmann::json j = {{"model", "spectral"},
                            {"grid_points", r.nx * r.ny},
                            {"nodes", r.nx * r.ny},
                            {"dofs", r.nx * r.ny},
                            {"ranks", 1},
                            {"threads", sc.threads},
                            {"thickness", o.body.half_space() ? nlohmann::json("inf") : nlohmann::json(o.body.thickness)},
                            {"wall_s", r.wall_s},
                            {"face_spacing", r.spacing},
                            {"rms_slope", o.rms_slope},
                            {"e_star", o.body.e_star()},
                            {"status", r.failed ? "failed" : "ok"},
                            {"steps", steps},
                            {"validity", validity.json},
                            {"provenance", prov.to_json()}};
  const ContactStep* peak = add_curve_summaries(j, r.steps, talk, surface.map);
  write_contact_files(c, j, r.steps, r.nx, r.ny, r.spacing, prov);
  outputs.commit();
  if (r.failed)
    return report_failure(c, r.steps, o.shear ? "relative change per geometry iteration" : "Polonsky-Keer error per iteration");
  if (talk) {
    std::printf("  %zu grid points, %d FFT thread(s)\n", r.nx * r.ny, sc.threads > 0 ? sc.threads : hardware_threads());
    print_peak(peak, r.steps);
    std::printf("  timing [s]: setup %.2f  solve %.2f  total %.2f\n", r.wall_setup, t_sol, r.wall_s);
  }
  return 0;
}

int run_contact(ContactCli c) {
  if (c.problem != "normal" && c.problem != "shear") throw InputError("--problem", "must be normal or shear");
  ContactModel model = ContactModel::fem;
  if (c.model != "auto") {
    try {
      model = parse_model(c.model);
    } catch (const std::invalid_argument& e) {
      throw InputError("--model", e.what());
    }
  }
  finish_scene_options(c.sc);
  const ContactScene& sc = c.sc.scene;
  // Every option checked before the work: the scene's as the sweeps check theirs. Under auto the
  // model is chosen later; load control (--pressure) then means a model other than the FEM.
  const ContactModel checked = c.model != "auto" ? model : sc.pressure > 0 ? ContactModel::spectral : ContactModel::fem;
  check_contact_scene(scene_of(c, checked));
  // Every output checked (and staged) before the work; rank 0 writes them.
  OutputSet outputs(launch_rank_and_size().first == 0);
  outputs.input(c.surface);
  outputs.input(c.wet);
  c.json_stage = outputs.add("--json", c.json);
  c.out_stage = outputs.add("--out", c.out);
  const std::string vtu_stage = outputs.add("--vtu", c.vtu);
  if (!c.wet.empty()) check_wet_file(c.wet, c.surface);
  const LoadedSurface s = load_surface(c.wet.empty() ? c.surface : c.wet);
  require_periodic_map(s, "the contact scene repeats the surface");
  if (launch_rank_and_size().first == 0) print_load_warnings(s);  // also under -q
  ContactRequest req;
  req.shear = c.problem == "shear";
  req.refine = sc.refine;
  req.load_control = sc.pressure > 0;
  req.pressure = sc.pressure;
  req.rms_slope = rms_slope_finite_difference(s.map);
  req.e_star = sc.young / (1 - sc.poisson * sc.poisson);
  if (c.model == "auto") {
    const ModelChoice choice = choose_model(req);
    std::string why;
    for (const auto& [m, checks] : choice.considered)
      for (const auto& v : checks)
        why += std::string("\n  ") + model_name(m) + ": " + v.name + (v.passed ? " passed" : " FAILED") + " (" +
               v.detail + ")";
    if (!choice.found) throw InputError("--model auto", "no model passes its validity checks:" + why);
    model = choice.model;
    if (!c.quiet) std::fprintf(stderr, "model auto: %s, the cheapest model whose checks pass:%s\n", model_name(model), why.c_str());
  }
  if (model != ContactModel::fem) {
    const auto [rank, size] = launch_rank_and_size();
    if (rank > 0) return 0;  // one process does the work (on threads); the others idle
    if (size > 1 && !c.quiet)
      std::fprintf(stderr, "note: the %s model runs on threads in one process; %d MPI ranks idle\n", model_name(model),
                   size - 1);
  }
  Validity validity{model, validity_checks(model, req), {}};
  validity.json = validity_json(model, validity.checks, c.model == "auto" ? "auto" : "user");
  if (model != ContactModel::fem && (!c.checkpoint.empty() || !c.restart.empty()))
    throw InputError(c.restart.empty() ? "--checkpoint" : "--restart",
                     std::string("the ") + model_name(model) + " model takes seconds per step: checkpoints are for fem");
  if (model != ContactModel::fem && !c.vtu.empty())
    throw InputError("--vtu", std::string("the ") + model_name(model) + " model has no block to write; --vtu is for fem");
  if (model == ContactModel::analytic) return run_analytic(c, s, req, validity, outputs);
  if (model == ContactModel::spectral) return run_spectral(c, s, validity, outputs);
  if (sc.pressure > 0) throw InputError("--pressure", "the fem model is displacement-controlled; give --uz");
  if (!(sc.uz > 0)) throw InputError("--uz", "the normal displacement must be > 0 m");
  const ContactScene scene = scene_of(c, ContactModel::fem);
  if (scene.shear && scene.ux == 0) throw InputError("--ux", "the shear test needs a tangential displacement");
  // On a wet obstacle the penetration limit is the ground's, as in the sweeps.
  const std::optional<LoadedSurface> ground = c.wet.empty() ? std::nullopt : std::optional(load_surface(c.surface));
  SceneRunHooks hooks;
  hooks.face_maps = !c.out.empty();
  hooks.progress_every_s = c.quiet ? 0 : 10;
  hooks.trace = c.trace;
  hooks.vtu_path = vtu_stage;
  hooks.checkpoint_path = c.checkpoint;
  hooks.restart_path = c.restart;
  hooks.ground = ground ? &ground->map : nullptr;
  // Every option checked before PETSc starts (comm MPI_COMM_NULL: PETSC_COMM_WORLD at run time).
  fem_test_options(scene, s.map, ground ? ground->map : s.map, MPI_COMM_NULL, hooks);

  int argc = 1;
  char name[] = "wetroad";
  char* args[] = {name, nullptr};
  char** argv = args;
  // Options go in before initialisation so that start-up options such as -log_view work.
  if (!c.petsc.empty()) PetscOptionsInsertString(nullptr, c.petsc.c_str());
  PetscSession petsc(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  const bool talk = rank == 0 && !c.quiet;
  if (rank == 0) warn_if_invalid(model, validity.checks);
  hooks.on_setup = [&](const SceneSetup& g) {
    if (!talk) return;
    std::printf("%s: %zux%zu obstacle, dx %.4g m, rms slope %.4g (triangulated); block %s, refine %d\n", s.source.c_str(),
                g.nx, g.ny, g.dx, g.rms_slope, scene.height > 0 ? "custom height" : "cube", scene.refine);
    print_step_header();
  };
  int k = 0;
  hooks.on_step = [&](const ContactStep& st) {
    ++k;
    if (talk) print_step_row(k, st);
  };
  const SceneResult run = [&] {
    try {
      return run_contact_scene(s.map, scene, MPI_COMM_NULL, hooks);
    } catch (const PetscFailure& e) {
      if (!c.petsc.empty() && e.bad_option()) throw InputError("--petsc \"" + c.petsc + "\"", e.what());
      throw;
    }
  }();
  const ContactTestResult& r = *run.fem;
  const ContactTestOptions& opt = *run.fem_options;
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& st : r.steps) steps.push_back(contact_step_json(st));
  if (opt.shear && opt.follow_geometry) {  // known only now: did the friction settle?
    validity.checks.push_back(friction_convergence_check(r.steps));
    validity.checks.push_back(friction_peak_check(r.steps));
    validity.json = validity_json(model, validity.checks, validity.json["chosen_by"].get<std::string>());
    if (rank == 0) warn_if_invalid(model, std::vector<ValidityCheck>(validity.checks.end() - 2, validity.checks.end()));
  }
  Provenance prov;
  prov.command = "contact";
  prov.inputs = {{"surface", c.surface}, {"wet", c.wet}};
  // The scene as the sweeps record it, with what the run resolved (the penetration limit in m,
  // the AMG hierarchy asked for) and the PETSc options.
  prov.parameters = contact_scene_json(scene);
  prov.parameters["problem"] = c.problem;
  prov.parameters["max_penetration"] = opt.max_penetration;
  prov.parameters["amg"] = c.sc.amg;
  prov.parameters["petsc"] = c.petsc;
  prov.model = std::string("fem: trilinear bricks graded in depth and in-plane (hanging nodes constrained), iterative "
                           "Signorini (thesis Alg. 1), PDAS + CG/GAMG; constraint normal: ") +
               (opt.block_normals > 0 ? "the block's face normal (experimental, not a rigid obstacle's force)"
                : opt.facet_normals   ? "the obstacle facet's"
                                        : "the obstacle's smooth vertex-normal blend");
  double t_lin = 0, t_rot = 0, t_sol = 0;
  for (const auto& st : r.steps) {
    t_lin += st.wall_linearise;
    t_rot += st.wall_rotate;
    t_sol += st.wall_solve;
  }
  prov.timings = {{"setup", r.wall_setup}, {"linearise", t_lin}, {"rotate", t_rot}, {"solve", t_sol},
                  {"total", r.wall_s}};
  nlohmann::json j = {{"model", "fem"},
                      {"nodes", r.nodes},
                      {"dofs", r.dofs},
                      {"ranks", ranks},
                      {"wall_s", r.wall_s},
                      {"face_nodes", r.face_nodes},
                      {"mesh_points", r.mesh_points},
                      {"elements", r.elements},
                      {"layers", r.layers},
                      {"coarsenings", r.coarsenings},
                      {"amg", amg_hierarchy_name(r.amg)},
                      {"solver", linear_solver_name(r.solver)},
                      {"face_spacing", r.face_spacing},
                      {"rms_slope", r.rms_slope},
                      {"e_star", r.e_star},
                      {"status", r.failed ? "failed" : "ok"},
                      {"steps", steps},
                      {"validity", validity.json},
                      {"provenance", prov.to_json()}};
  if (r.restart) {  // the kept steps were solved with the checkpoint's run's options
    const RestartableOptions& o = r.restart->kept_options;
    j["restart"] = {{"checkpoint", r.restart->checkpoint},
                    {"steps_kept", r.restart->steps_kept},
                    {"their_options",
                     {{"--ux", o.ux}, {"--shear-steps", o.shear_steps}, {"--cutbacks", o.max_cutbacks},
                      {"--tol", o.tolerance}, {"--max-penetration", o.max_penetration}}}};
  }
  const ContactStep* peak = add_curve_summaries(j, r.steps, talk, s.map);
  if (rank == 0) write_contact_files(c, j, r.steps, r.face_nx, r.face_ny, r.face_spacing, prov);
  if (r.steps.empty()) outputs.discard("--vtu");  // no step: no deformed block to show
  outputs.commit();
  if (r.failed) return rank == 0 ? report_failure(c, r.steps, "relative change per Signorini iteration") : 3;
  if (talk) {
    std::printf("  %zu nodes (%zu with hanging), %zu bricks in %d layers, %d in-plane coarsenings, %zu dofs, %d rank(s), "
                "%s\n",
                r.nodes, r.mesh_points, r.elements, r.layers, r.coarsenings, r.dofs, ranks,
                r.solver == LinearSolver::direct ? "sparse Cholesky (direct)"
                : r.solver == LinearSolver::gmg  ? "matrix-free, geometric multigrid"
                                                 : (std::string(amg_hierarchy_name(r.amg)) + " AMG hierarchy").c_str());
    print_peak(peak, r.steps);
    std::printf("  timing [s]: setup %.2f  linearise %.2f  rotate %.2f  solve %.2f  total %.2f\n", r.wall_setup,
                t_lin, t_rot, t_sol, r.wall_s);
  }
  return 0;
}

}  // namespace

Command add_contact(CLI::App& root) {
  auto c = std::make_shared<ContactCli>();
  CLI::App* s = root.add_subcommand("contact", "press (and shear) an elastic block on a road surface (FEM or spectral)");
  s->footer(
      "Problem A (normal): the top face of an elastic block (side = the surface period, a cube by default)\n"
      "is pushed down by --uz in --steps steps onto the rigid periodic obstacle; the bottom face is the\n"
      "frictionless, non-adhesive contact boundary. Problem B (shear): after A, the top is pushed along x\n"
      "by --ux in --steps steps; mu = Fx / Fz. Contact: the thesis's iterative Signorini scheme (rays along\n"
      "the deformed face normals against the triangulated obstacle, constraints rotated into the obstacle's\n"
      "normal frames, primal-dual active set with CG + GAMG, damped corrections). MPI: mpirun -np N.\n"
      "Mesh: trilinear bricks; the face lattice (surface spacing / --refine) for --layers layers, then the\n"
      "in-plane spacing doubles every --layers layers while the cell counts stay even (hanging nodes\n"
      "constrained); the coarsest level thickens geometrically up to the top.\n"
      "--model spectral: the periodic counterpart, an elastic layer (--thickness, default the block height)\n"
      "with its far face displaced by --uz, or a half-space (--thickness inf) under a mean --pressure;\n"
      "FFT boundary elements, Polonsky-Keer constrained CG (normal load only so far; small slopes).\n"
      "It runs on FFT threads (--threads), not on MPI ranks.\n"
      "Example: wetroad contact --surface road.h5 --problem shear --uz 9e-3 --ux 1e-3 --json mu.json\n"
      "         wetroad contact --surface road.h5 --model spectral --thickness inf --pressure 0.01 --steps 10");
  // `contact`'s defaults: a finer face and a tighter iteration than the sweeps' many runs use.
  ContactScene& sc = c->sc.scene;
  sc.refine = 2;
  sc.tolerance = 1e-5;
  sc.normal_steps = 4;
  sc.shear_steps = 0;  // as --steps
  sc.threads = 0;      // spectral FFT threads: all cores
  s->add_option("--surface", c->surface, "surface file (periodic HDF5 height map)")->type_name("FILE")->required();
  s->add_option("--wet", c->wet, "wet surface from `wetroad fill` (used as the obstacle instead)")->type_name("FILE");
  s->add_option("--problem", c->problem, "normal (Problem A) or shear (Problem B)")->capture_default_str();
  s->add_option("--model", c->model,
                "contact model: analytic (Persson/BGT, needs --pressure), spectral (periodic layer / half-space), fem "
                "(finite block), or auto (the cheapest whose validity checks pass)")
      ->capture_default_str();
  add_scene_options(*s, c->sc);
  s->add_option("--pressure", sc.pressure, "analytic and spectral models: final mean pressure, Pa (load control; instead of --uz)");
  s->add_option("--threads", sc.threads, "spectral model: FFT threads (default: all cores)")->check(CLI::NonNegativeNumber);
  s->add_option("--json", c->json, "write the per-step results as JSON (SI units)")->type_name("OUTPUT");
  s->add_option("--out", c->out, "write per-step contact-face maps (pressure Pa, gap m, status) to HDF5")->type_name("OUTPUT");
  s->add_option("--vtu", c->vtu, "write the deformed block of the last step for ParaView (.vtu)")->type_name("OUTPUT");
  s->add_option("--checkpoint", c->checkpoint,
                "fem: after every converged load step, save the run's state to FILE (and FILE.0.*, FILE.1.*), so "
                "that --restart can continue it after a kill or a wall-time limit")
      ->type_name("FILE");
  s->add_option("--restart", c->restart,
                "fem: continue the run from the checkpoint FILE (same surface, options and rank count; the steps it "
                "holds are reported as this run's); may name the --checkpoint file. A larger --ux (or other "
                "--shear-steps) shears on from the checkpoint's last step, except with --to-peak; other --cutbacks, --tol "
                "and --max-penetration apply to the steps to come (the JSON's \"restart\" says what the kept ones had)")
      ->type_name("FILE");
  s->add_option("--petsc", c->petsc, "PETSc options, e.g. \"-ksp_monitor -log_view\"");
  s->add_flag("-q,--quiet", c->quiet, "print nothing on success");
  s->add_flag("--trace", c->trace, "print every Signorini iteration (change, contact nodes, iterations, forces, deepest node of the iterate and of u*, time); with --iteration newton also, after each converged step, whether the whole curvature term leaves the system definite there (docs/fem-solver.md, the second-order check)");
  return {s, [c] { return run_contact(*c); }};
}

}  // namespace wr::app
