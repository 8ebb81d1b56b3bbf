// Benchmarks across the model ladder: spectral against FEM, speed against accuracy, FEM mesh convergence (bench/bench_harness.hpp).
#include "bench/bench_harness.hpp"
#include "bench/bench_common.hpp"

#include "lib/fem/amg_hierarchy.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "lib/analytic/contact_theory.hpp"
#include "lib/analytic/hertz.hpp"
#include "lib/analytic/nayak_summits.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/core/provenance.hpp"
#include "lib/core/richardson.hpp"
#include "lib/scene/contact_scene.hpp"
#include "lib/contact/contact_step.hpp"
#include "lib/contact/friction_convergence.hpp"
#include "lib/core/fft.hpp"
#include "lib/contact/periodic_obstacle.hpp"
#include "lib/fem/block_press_shear.hpp"
#include "lib/fem/elastic_block.hpp"
#include "lib/spectral/normal_contact.hpp"
#include "lib/spectral/spectral_press_shear.hpp"
#include "roads/height_stats.hpp"
#include "reports/plot.hpp"
#include "roads/analyze.hpp"
#include "roads/surface_file.hpp"
#include "roads/surface_import.hpp"
#include "roads/synthesize.hpp"
#include "water/depression_hierarchy.hpp"
#include "water/drained_limit.hpp"
#include "water/fill_spill_merge.hpp"
#include "water/rain_fill.hpp"

namespace wr::bench {
namespace {

// The comparison scene of spectral_vs_fem and accuracy: 100 x 100, 0.1 mm spacing (1 cm
// period), H 0.7, q0 = 2 qL, seed 3.
HeightMap comparison_scene(double h0) {
  SynthParams sp;
  sp.nx = sp.ny = 100;
  sp.dx = 1e-4;
  sp.h0 = h0;
  sp.hurst = 0.7;
  sp.q0_ratio = 2;
  sp.seed = 3;
  sp.threads = 1;
  return synthesize(sp).map;
}

// Its press: about a third of contact whatever h0 (uz proportional to h0), two steps.
constexpr int kComparisonPressSteps = 2;
constexpr double kComparisonTolerance = 1e-4;
double comparison_uz(double h0) { return 2.5e-4 * h0 / 3e-5; }

// The press as FEM options (the accuracy bench's runs).
ContactTestOptions comparison_press(double h0, int refine, double slope) {
  ContactTestOptions fo;
  fo.uz = comparison_uz(h0);
  fo.normal_steps = kComparisonPressSteps;
  fo.refine = refine;
  fo.tolerance = kComparisonTolerance;
  fo.rms_slope = slope;
  return fo;
}

// The press and then a shear test, as a scene both models run: the top moved by half the
// press in two steps (the face slides several lattice cells on the gentle scenes, about one on
// the steepest).
ContactScene comparison_shear(double h0, int refine) {
  ContactScene sc;
  sc.uz = comparison_uz(h0);
  sc.normal_steps = kComparisonPressSteps;
  sc.ux = sc.uz / 2;
  sc.shear_steps = 2;
  sc.refine = refine;
  sc.tolerance = kComparisonTolerance;
  return sc;
}

// mu of a shear run's last step; NaN when it did not get there.
double final_mu(const SceneResult& r, const ContactScene& sc) {
  const std::size_t n = std::size_t(sc.normal_steps + sc.shear_steps);
  return r.steps.size() == n && !r.failed ? r.steps.back().mu : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

nlohmann::json spectral_vs_fem(const std::vector<double>& h0s, int refine, int rank) {
  nlohmann::json rows = nlohmann::json::array();
  for (double h0 : h0s) {
    const HeightMap m = comparison_scene(h0);
    const double slope = rms_slope_finite_difference(m, 1);
    // One FEM run gives both: A/A0 at the end of its press, mu at the end of its shear.
    ContactScene shear = comparison_shear(h0, refine);
    shear.model = ContactModel::fem;
    double t0 = now();
    const SceneResult fr = run_contact_scene(m, shear, MPI_COMM_NULL);
    const double fem_wall = now() - t0;
    if (fr.steps.empty()) throw std::runtime_error("spectral-vs-fem: no FEM step finished at h0 " + std::to_string(h0) + " m");
    // The press's last step (or the last that finished; fem_converged says which).
    const ContactStep& fs = fr.steps[std::min(fr.steps.size(), std::size_t(shear.normal_steps)) - 1];
    const double fem_mu = final_mu(fr, shear);
    nlohmann::json row = {{"h0", h0}, {"rms_slope", slope}, {"refine", refine}, {"fem_nodes", fr.unknowns},
                          {"fem_fz", fs.fz}, {"fem_area_fraction", fs.area_fraction}, {"fem_converged", !fr.failed},
                          {"fem_wall_s", fem_wall}, {"uz", shear.uz}, {"ux", shear.ux}, {"fem_mu", fem_mu}};
    if (rank == 0) {
      // The spectral layer (thickness = the period) at the FEM's mean pressure, on the same face lattice.
      SpectralTestOptions so;
      so.pressure = fs.fz / (m.lx() * m.ly());
      so.steps = 2;
      so.body = ElasticBody{shear.young, shear.poisson, m.lx()};
      so.rms_slope = slope;
      so.solver.threads = 1;
      t0 = now();
      const SpectralTestResult r = run_spectral_contact_test(resample_triangulated(m, refine), so);
      row["spectral_area_fraction"] = r.steps.back().area_fraction;
      row["spectral_converged"] = !r.failed;
      row["spectral_wall_s"] = now() - t0;
      row["area_difference"] = r.steps.back().area_fraction / fs.area_fraction - 1;
      // mu compared at equal displacements: the layer is stiffer than the cube at equal uz,
      // but a frictionless mu does not scale with the load, and equal pressure cannot be set
      // under displacement control.
      t0 = now();
      shear.model = ContactModel::spectral;  // on the FEM's face lattice, a layer as thick as the cube
      const SceneResult rs = run_contact_scene(m, shear, MPI_COMM_NULL);
      const double spectral_mu = final_mu(rs, shear);
      row["spectral_shear_converged"] = !rs.failed;
      row["spectral_shear_wall_s"] = now() - t0;
      row["spectral_mu"] = spectral_mu;
      // mu of a frictionless contact is a mean of local slopes weighted by pressure, so its
      // scale is the rms slope: the difference is reported relative to it.
      row["mu_difference_per_slope"] = (spectral_mu - fem_mu) / slope;
      std::fprintf(stderr, "  h0 %.3g m (rms slope %.3f) done: FEM %.1f s\n", h0, slope, fem_wall);
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace wr::bench

namespace wr::bench {

void plot_spectral_vs_fem(const nlohmann::json& rows, const std::string& path) {
  PlotSpec p;
  p.title = "Spectral layer against the FEM block: A/A0 at equal mean pressure, mu at equal displacements";
  p.xlabel = "rms slope";
  p.ylabel = "difference, %";
  const std::string refine = "refine " + std::to_string(rows.empty() ? 0 : rows[0]["refine"].get<int>());
  PlotSeries area{"A/A0: spectral / FEM - 1, " + refine, {}, {}, "linespoints", {}};
  PlotSeries mu{"mu: (spectral - FEM) / rms slope, " + refine, {}, {}, "linespoints", {}};
  for (const auto& r : rows) {
    area.x.push_back(r["rms_slope"].get<double>());
    area.y.push_back(100 * r["area_difference"].get<double>());
    mu.x.push_back(r["rms_slope"].get<double>());
    mu.y.push_back(100 * r["mu_difference_per_slope"].get<double>());
  }
  p.series.push_back(area);
  p.series.push_back(mu);
  write_svg_plot(path, p);
}

}  // namespace wr::bench

namespace wr::bench {

nlohmann::json accuracy(double h0, const std::vector<int>& fem_refines, const std::vector<int>& spectral_refines,
                        int rank) {
  const HeightMap m = comparison_scene(h0);
  const double slope = rms_slope_finite_difference(m, 1), a0 = m.lx() * m.ly();
  nlohmann::json points = nlohmann::json::array();
  // FEM first (displacement-controlled: its mean pressure moves a little with the mesh); the
  // finest FEM's mean pressure is the load of the spectral and analytic points, so that they
  // meet the reference at equal load.
  double pressure = 0;
  for (int r : fem_refines) {
    const ContactTestOptions fo = comparison_press(h0, r, slope);
    const double t0 = now();
    const ContactTestResult fr = run_contact_test(m, fo);
    const ContactStep& st = fr.steps.back();
    pressure = st.fz / a0;
    points.push_back({{"model", "fem"}, {"refine", r}, {"nodes", fr.nodes}, {"pressure", st.fz / a0},
                      {"area_fraction", st.area_fraction}, {"wall_s", now() - t0}, {"converged", !fr.failed}});
    if (rank == 0) std::fprintf(stderr, "  fem refine %d: %.1f s\n", r, now() - t0);
  }
  if (rank == 0) {
    for (int r : spectral_refines) {
      SpectralTestOptions so;
      so.pressure = pressure;
      so.steps = 2;
      so.body = ElasticBody{1.0, 0.45, m.lx()};
      so.rms_slope = slope;
      so.solver.threads = 1;
      const double t0 = now();
      const HeightMap fine = resample_triangulated(m, r);
      const SpectralTestResult res = run_spectral_contact_test(fine, so);
      points.push_back({{"model", "spectral"}, {"refine", r}, {"nodes", fine.size()}, {"pressure", pressure},
                        {"area_fraction", res.steps.back().area_fraction}, {"wall_s", now() - t0},
                        {"converged", !res.failed}});
    }
    const double t0 = now();
    const double sigma = pressure / (1.0 / (1 - 0.45 * 0.45) * slope);
    points.push_back({{"model", "analytic"}, {"refine", 0}, {"nodes", 0}, {"pressure", pressure},
                      {"area_fraction", persson_area_fraction(sigma)}, {"wall_s", std::max(now() - t0, 1e-7)},
                      {"converged", true}});
    // The reference: the finest FEM (the last in the list); errors of A/A0 against it.
    double ref = 0;
    for (const auto& p : points)
      if (p["model"] == "fem") ref = p["area_fraction"].get<double>();
    for (auto& p : points) p["error"] = std::abs(p["area_fraction"].get<double>() / ref - 1);
  }
  return {{"h0", h0}, {"rms_slope", slope}, {"reference", "finest FEM"}, {"points", points}};
}

void plot_accuracy(const nlohmann::json& result, const std::string& path) {
  PlotSpec p;
  p.title = "A/A0 of one scene: wall time against the error to the finest FEM";
  p.xlabel = "wall time, s";
  p.ylabel = "|A/A0 / A/A0(finest FEM) - 1|";
  p.logx = p.logy = true;
  for (const char* model : {"analytic", "spectral", "fem"}) {
    PlotSeries s{model, {}, {}, "linespoints", {}};
    for (const auto& q : result["points"])
      if (q["model"] == model && q["error"].get<double>() > 0) {
        s.x.push_back(q["wall_s"].get<double>());
        s.y.push_back(q["error"].get<double>());
      }
    if (!s.x.empty()) p.series.push_back(s);
  }
  write_svg_plot(path, p);
}

}  // namespace wr::bench

namespace wr::bench {
namespace {

// Nodes per face node of the graded cube (300 x 300 obstacle: 2.90 at refine 2, 2.73 at
// refine 4) and the share of memory up to which a lean-hierarchy run is tried (300 x 300 at
// refine 4: 3.93M nodes ran in 19.5 GiB of 23.5 GiB, 83 %); with fem_memory_estimate a pre-flight
// check that decides whether a mesh is tried. The block picks its hierarchy itself (automatic).
constexpr double kNodesPerFaceNode = 2.8, kLeanMemoryShare = 0.9;

double estimated_fem_bytes(const HeightMap& m, int refine, double memory) {
  const double face = double(m.nx * std::size_t(refine) + 1) * double(m.ny * std::size_t(refine) + 1);
  const double nodes = kNodesPerFaceNode * face;
  return fem_memory_estimate(nodes, resolve_amg_hierarchy(AmgHierarchy::automatic, nodes, memory));
}

}  // namespace

nlohmann::json fem_mesh_convergence(const HeightMap& surface, const ContactScene& base, const std::vector<int>& refines,
                                    int rank) {
  nlohmann::json rows = nlohmann::json::array();
  const double memory = double(physical_memory_bytes());
  for (int r : refines) {
    ContactScene sc = base;
    sc.model = ContactModel::fem;
    sc.refine = r;
    const double need = estimated_fem_bytes(surface, r, memory);
    nlohmann::json row = {{"refine", r}, {"face_spacing", surface.dx / r}, {"estimated_bytes", need}};
    if (need > kLeanMemoryShare * memory) {
      row["skipped"] = "estimated " + human_bytes(need) + " of " + human_bytes(memory) + " physical memory";
      if (rank == 0) std::fprintf(stderr, "  refine %d skipped: %s\n", r, row["skipped"].get<std::string>().c_str());
      rows.push_back(row);
      continue;
    }
    const double t0 = now();
    const SceneResult fr = run_contact_scene(surface, sc, MPI_COMM_NULL);
    row["wall_s"] = now() - t0;
    row["nodes"] = fr.unknowns;
    row["converged"] = !fr.failed;
    row["peak_rss_bytes"] = double(peak_rss_bytes());  // this process so far (rank 0 reports its own)
    if (fr.area_normal > 0) row["pressed_area_fraction"] = fr.area_normal;
    if (const ContactStep* p = peak_friction(fr.steps)) {
      row["mu"] = p->mu;
      row["mu_ux"] = p->ux;
      row["mu_drift"] = p->mu_drift;
      // The iteration met --tol while mu still crept (friction_convergence.hpp): such a mu is
      // where the iteration stopped, so the extrapolation that uses it says so.
      row["friction_converged"] = !(p->mu_drift > kFrictionDriftLimit);
      row["sheared_area_fraction"] = p->area_fraction;
    }
    if (fr.failed) row["message"] = fr.message;
    if (rank == 0)
      std::fprintf(stderr, "  refine %d: %zu nodes, %.1f s%s\n", r, fr.unknowns, now() - t0, fr.failed ? ", FAILED" : "");
    rows.push_back(row);
  }
  // Richardson over each run of three successive finished meshes with one refinement ratio.
  nlohmann::json extrapolations = nlohmann::json::array();
  for (std::size_t k = 2; k < rows.size(); ++k) {
    const nlohmann::json &a = rows[k - 2], &b = rows[k - 1], &c = rows[k];
    const double ratio = double(b["refine"].get<int>()) / a["refine"].get<int>();
    if (std::abs(double(c["refine"].get<int>()) / b["refine"].get<int>() - ratio) > 1e-12 || ratio <= 1) continue;
    nlohmann::json e = {{"refines", {a["refine"], b["refine"], c["refine"]}}, {"ratio", ratio}};
    for (const char* q : {"mu", "pressed_area_fraction", "sheared_area_fraction"}) {
      if (!a.contains(q) || !b.contains(q) || !c.contains(q)) continue;
      const auto r = richardson_three(a[q].get<double>(), b[q].get<double>(), c[q].get<double>(), ratio);
      e[q] = r ? nlohmann::json{{"order", r->order}, {"limit", r->limit}, {"error", r->error}}
               : nlohmann::json{{"asymptotic", false}};
      // Beside the verdict, how far the two finest meshes still are apart: a sign change of a
      // difference far below the previous one is convergence within it, not divergence.
      e[q]["finest_difference"] = std::abs(c[q].get<double>() - b[q].get<double>());
    }
    if (e.contains("mu"))
      e["mu"]["friction_converged"] = a.value("friction_converged", false) && b.value("friction_converged", false) &&
                                      c.value("friction_converged", false);
    extrapolations.push_back(e);
  }
  return {{"meshes", rows}, {"extrapolations", extrapolations}};
}

void plot_mesh_convergence(const nlohmann::json& result, const std::string& path) {
  PlotSpec p;
  p.title = "FEM shear test: peak mu against face spacing";
  p.xlabel = "face spacing / obstacle spacing";
  p.ylabel = "mu";
  p.logx = true;
  PlotSeries s{"peak mu (converged meshes)", {}, {}, "linespoints", {}};
  for (const auto& r : result["meshes"])
    if (r.contains("mu") && r.value("converged", false)) {
      s.x.push_back(1.0 / r["refine"].get<int>());
      s.y.push_back(r["mu"].get<double>());
    }
  p.series.push_back(s);
  // The finest extrapolation that found a limit, drawn left of the finest mesh with its GCI band.
  const auto& ex = result["extrapolations"];
  for (auto e = ex.rbegin(); e != ex.rend() && !s.x.empty(); ++e) {
    if (!e->contains("mu") || !(*e)["mu"].contains("limit")) continue;
    const auto& k = (*e)["refines"];
    const std::string label = "Richardson limit over refine " + std::to_string(k[0].get<int>()) + ", " +
                              std::to_string(k[1].get<int>()) + ", " + std::to_string(k[2].get<int>()) + " (GCI band)";
    p.series.push_back({label, {s.x.back() / 2}, {(*e)["mu"]["limit"].get<double>()}, "points",
                        {(*e)["mu"]["error"].get<double>()}});
    break;
  }
  write_svg_plot(path, p);
}

}  // namespace wr::bench
