#include "roads/analyze.hpp"

#include <cmath>

#include "lib/analytic/contact_theory.hpp"
#include "lib/analytic/nayak_summits.hpp"
#include "lib/io/hdf5_file.hpp"
#include "roads/height_stats.hpp"
#include "roads/summits.hpp"

namespace wr {
namespace {

nlohmann::json opt_json(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::json num_json(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// The prescribed continuous spectrum: the eq. 4.4 plateau (what the thesis integrates), cut.
SelfAffinePsd continuous_psd(const SynthesisRecord& s) {
  SelfAffinePsd p = s.psd;
  p.k = s.k_eq44;
  return p;
}

SurfaceFigures prescribed_figures(const SynthesisRecord& s, const std::optional<ExpectedMpd>& e) {
  const SelfAffinePsd p = continuous_psd(s);
  SurfaceFigures f;
  f.m0 = p.m0();
  f.m2 = p.m2();
  f.m4 = p.m4();
  f.alpha = p.alpha();
  f.h0 = std::sqrt(*f.m0);
  f.rms_slope_spectral = std::sqrt(2 * *f.m2);
  f.hurst = p.hurst;
  f.q0 = p.q0;
  f.plateau = s.psd.k;  // the plateau actually synthesized (lattice-normalised)
  f.summit_density = nayak_summit_density(*f.m2, *f.m4);
  if (*f.alpha > 1.5) {
    const auto g = greenwood_summit_moments(*f.alpha);
    f.summit_mean = g.mean;
    f.summit_var = g.variance;
  }
  if (e) {
    f.mpd = e->mpd;
    f.mpd_std = e->mpd_std;
    f.etd = estimated_texture_depth(e->mpd);
  }
  return f;
}

}  // namespace

AnalysisReport analyze_surface(const LoadedSurface& s, const AnalysisOptions& opt) {
  AnalysisReport r;
  const HeightMap& m = s.map;
  r.source = s.source;
  r.format = s.format;
  r.nx = m.nx;
  r.ny = m.ny;
  r.dx = m.dx;
  r.dy = m.dy;
  r.profile = m.is_profile();
  r.periodic = m.periodic;
  r.dropouts = s.dropouts;
  r.tilt_x = s.tilt_x;
  r.tilt_y = s.tilt_y;
  r.offset = s.offset;

  r.timer.start("spectrum");
  const SpectrumResult spec = analyze_spectrum(m, opt.threads);
  r.psd = spec.psd;
  r.moments = spec.moments;
  r.nyquist = spec.nyquist;
  r.rms_slope_spectral = std::sqrt(2 * r.moments.m2);

  r.timer.start("psd fit");
  r.fit = fit_self_affine(r.psd, r.nyquist, r.profile);

  r.timer.start("height statistics");
  const HeightStats hs = height_stats(m, opt.threads);
  r.h0 = hs.sq;
  r.sa = hs.sa;
  r.ssk = hs.ssk;
  r.sku = hs.sku;
  r.rms_slope_fd = rms_slope_finite_difference(m, opt.threads);
  r.rms_slope_central = rms_slope_finite_difference(m, opt.threads, SlopeStencil::central);

  const double alpha = r.moments.alpha();
  if (!r.profile) {
    r.timer.start("summits");
    SummitStats ss = find_summits(m, r.h0, opt.threads);
    r.summit_count = ss.count;
    r.summit_density = ss.density;
    if (ss.count > 0) {
      r.summit_mean = ss.mean;
      r.summit_var = ss.variance;
    }
    r.nayak_density = nayak_summit_density(r.moments.m2, r.moments.m4);
    if (alpha > 1.5) {
      const auto nm = nayak_summit_moments(alpha);
      const auto gw = greenwood_summit_moments(alpha);
      r.nayak_mean = nm.mean;
      r.nayak_var = nm.variance;
      r.greenwood_mean = gw.mean;
      r.greenwood_var = gw.variance;
      if (ss.count > 0) r.summit_ks = ks_distance_to_nayak(ss.xi, alpha);
    }
    r.summit_xi = std::move(ss.xi);
  }

  r.timer.start("mpd");
  r.mpd = mpd_of_map(m, s.dropout, opt.mpd, opt.threads);

  r.timer.start("analytic");
  r.kappa_persson = kappa_persson();
  r.kappa_bgt = kappa_bgt();
  for (double ss : opt.sigma_stars) r.persson_area.emplace_back(ss, persson_area_fraction(ss));

  if (s.synthesis) {
    r.synthesis = s.synthesis;
    if (opt.expected_mpd) {
      r.timer.start("expected mpd");
      ExpectedMpdOptions eo;
      eo.mpd = opt.mpd;
      r.expected_mpd = expected_mpd(continuous_psd(*s.synthesis), m.dx, eo);
    }
    r.timer.start("prescribed");
    r.prescribed = prescribed_figures(*s.synthesis, r.expected_mpd);
  }
  r.timer.stop();
  return r;
}

nlohmann::json AnalysisReport::to_json() const {
  using nlohmann::json;
  json j;
  j["nx"] = nx;
  j["ny"] = ny;
  j["dx"] = dx;
  j["dy"] = dy;
  j["h0"] = h0;
  j["sa"] = sa;
  j["ssk"] = ssk;
  j["sku"] = sku;
  j["rms_slope_spectral"] = rms_slope_spectral;
  j["rms_slope_fd"] = rms_slope_fd;
  j["rms_slope_central"] = rms_slope_central;
  j["m0"] = moments.m0;
  j["m2"] = moments.m2;
  j["m4"] = moments.m4;
  j["alpha"] = num_json(moments.alpha());
  j["hurst_fit"] = fit.ok ? json(fit.hurst) : json(nullptr);
  j["q0_fit"] = fit.ok ? json(fit.q0) : json(nullptr);
  j["plateau_fit"] = fit.ok ? json(fit.plateau_k) : json(nullptr);
  j["summit_density"] = opt_json(summit_density);
  j["summit_mean"] = opt_json(summit_mean);
  j["summit_var"] = opt_json(summit_var);
  j["mpd"] = num_json(mpd.mpd);
  j["mpd_std"] = num_json(mpd.mpd_std);
  j["etd"] = num_json(estimated_texture_depth(mpd.mpd));
  j["kappa_persson"] = kappa_persson;
  j["kappa_bgt"] = kappa_bgt;

  j["input"] = {{"source", source},   {"format", format},  {"kind", profile ? "profile" : "map"},
                {"periodic", periodic}, {"lx", nx * dx},     {"ly", profile ? 0.0 : ny * dy},
                {"dropouts", dropouts}, {"tilt_x", tilt_x}, {"tilt_y", tilt_y}, {"offset", offset}};
  j["psd_fit"] = {{"ok", fit.ok},       {"beta", fit.beta},   {"r2", fit.r2},       {"rms_log10", fit.rms_log10},
                  {"q_min", fit.q_min}, {"q_max", fit.q_max}, {"bins", fit.bins},   {"note", fit.note},
                  {"nyquist", nyquist}};
  if (!profile) {
    j["summits"] = {{"count", summit_count ? json(*summit_count) : json(nullptr)},
                    {"ks_distance", opt_json(summit_ks)},
                    {"nayak_density", opt_json(nayak_density)},
                    {"nayak_mean", opt_json(nayak_mean)},
                    {"nayak_var", opt_json(nayak_var)},
                    {"eq45_mean", opt_json(greenwood_mean)},
                    {"eq45_var", opt_json(greenwood_var)}};
  } else {
    j["summits"] = nullptr;
  }
  j["mpd_detail"] = {{"profiles", mpd.profiles},
                     {"segments", mpd.segments},
                     {"valid_segments", mpd.valid_segments},
                     {"spikes", mpd.spikes},
                     {"valid", mpd.valid},
                     {"mpd_x", num_json(mpd.mpd_x)},
                     {"mpd_y", num_json(mpd.mpd_y)},
                     {"spacing", mpd.spacing},
                     {"plate_start", mpd.plate_start},
                     {"plate_end", mpd.plate_end},
                     {"standard_baseline", mpd.standard_baseline},
                     {"baseline", mpd.baseline_used},
                     {"lowpass_applied", mpd.lowpass_applied},
                     {"note", mpd.note}};
  if (mpd.evaluation_length > 0) {
    json table = json::array();
    for (const EvaluationMpd& e : mpd.evaluations)
      table.push_back({{"profile", e.profile},
                       {"start", e.start},
                       {"length", e.length},
                       {"segments", e.segments},
                       {"valid_segments", e.valid_segments},
                       {"mpd", num_json(e.mpd)},
                       {"valid", e.valid},
                       {"complete", e.complete}});
    j["mpd_evaluation"] = {{"length", mpd.evaluation_length},     {"evaluations", mpd.evaluations.size()},
                           {"counted", mpd.evaluations_counted},  {"mean", num_json(mpd.evaluation_mean)},
                           {"min", num_json(mpd.evaluation_min)}, {"max", num_json(mpd.evaluation_max)},
                           {"table", std::move(table)}};
  } else {
    j["mpd_evaluation"] = nullptr;
  }
  json pa = json::array();
  for (const auto& [s, a] : persson_area) pa.push_back({{"sigma_star", s}, {"area_fraction", a}});
  j["persson_area"] = pa;
  if (synthesis) {
    const auto& p = prescribed;
    j["prescribed"] = {{"h0", opt_json(p.h0)},
                       {"rms_slope_spectral", opt_json(p.rms_slope_spectral)},
                       {"m0", opt_json(p.m0)},
                       {"m2", opt_json(p.m2)},
                       {"m4", opt_json(p.m4)},
                       {"alpha", opt_json(p.alpha)},
                       {"hurst_fit", opt_json(p.hurst)},
                       {"q0_fit", opt_json(p.q0)},
                       {"plateau_fit", opt_json(p.plateau)},
                       {"summit_density", opt_json(p.summit_density)},
                       {"summit_mean", opt_json(p.summit_mean)},
                       {"summit_var", opt_json(p.summit_var)},
                       {"mpd", opt_json(p.mpd)},
                       {"mpd_std", opt_json(p.mpd_std)},
                       {"etd", opt_json(p.etd)},
                       {"kappa_persson", kappa_persson},
                       {"kappa_bgt", kappa_bgt}};
    j["synthesis"] = {{"h0", synthesis->psd.h0},
                      {"hurst", synthesis->psd.hurst},
                      {"qL", synthesis->psd.qL},
                      {"q0", synthesis->psd.q0},
                      {"q1", synthesis->psd.q1},
                      {"q1_cut", synthesis->psd.q1_cut},
                      {"plateau_k", synthesis->psd.k},
                      {"plateau_k_eq44", synthesis->k_eq44},
                      {"h0_eq44_on_lattice", synthesis->h0_eq44_on_lattice},
                      {"eq44_h0_error", synthesis->h0_eq44_on_lattice / synthesis->psd.h0 - 1},
                      {"seed", synthesis->seed},
                      {"oversample", synthesis->oversample}};
    if (expected_mpd)
      j["expected_mpd"] = {{"mpd", num_json(expected_mpd->mpd)},
                           {"mpd_std", num_json(expected_mpd->mpd_std)},
                           {"std_error", num_json(expected_mpd->std_error)},
                           {"segments", expected_mpd->segments},
                           {"spacing", expected_mpd->spacing},
                           {"assumption", expected_mpd->assumption}};
  }
  j["timings"] = timer.to_json();
  return j;
}

void write_analysis_file(const std::string& path, const AnalysisReport& r, const Provenance& prov) {
  Hdf5Writer w(path);
  auto summary = r.to_json();
  // The per-evaluation-length table goes to /mpd_evaluation below: a 10 km record's 1000 rows would
  // overflow an HDF5 attribute (64 KiB).
  if (summary["mpd_evaluation"].is_object()) summary["mpd_evaluation"].erase("table");
  w.create_group("/psd");
  w.write_vector("/psd/q", r.psd.q);
  w.write_vector("/psd/C", r.psd.C);
  w.write_vector("/psd/count", r.psd.count);
  w.write_attr("/psd", "q_unit", std::string("1/m"));
  w.write_attr("/psd", "C_unit", std::string(r.profile ? "m^3" : "m^4"));
  if (!r.profile) {
    w.create_group("/summits");
    w.write_vector("/summits/xi", r.summit_xi);
  }
  if (!r.mpd.evaluations.empty()) {  // one row per evaluation length (ISO 13473-1 continuous records)
    const auto column = [&](auto get) {
      std::vector<double> v;
      v.reserve(r.mpd.evaluations.size());
      for (const EvaluationMpd& e : r.mpd.evaluations) v.push_back(double(get(e)));
      return v;
    };
    w.create_group("/mpd_evaluation");
    w.write_vector("/mpd_evaluation/profile", column([](const EvaluationMpd& e) { return e.profile; }));
    w.write_vector("/mpd_evaluation/start", column([](const EvaluationMpd& e) { return e.start; }));
    w.write_vector("/mpd_evaluation/length", column([](const EvaluationMpd& e) { return e.length; }));
    w.write_vector("/mpd_evaluation/segments", column([](const EvaluationMpd& e) { return e.segments; }));
    w.write_vector("/mpd_evaluation/valid_segments", column([](const EvaluationMpd& e) { return e.valid_segments; }));
    w.write_vector("/mpd_evaluation/mpd", column([](const EvaluationMpd& e) { return e.mpd; }));
    w.write_vector("/mpd_evaluation/valid", column([](const EvaluationMpd& e) { return e.valid; }));
    w.write_vector("/mpd_evaluation/complete", column([](const EvaluationMpd& e) { return e.complete; }));
    w.write_attr("/mpd_evaluation", "evaluation_length", r.mpd.evaluation_length);
    w.write_attr("/mpd_evaluation", "unit", std::string("m"));
  }
  for (const auto& [key, value] : summary.items())
    if (value.is_number()) w.write_attr("/", key, value.get<double>());
  w.write_attr("/", "summary", summary.dump());
  w.write_attr("/", "provenance", prov.to_json().dump());
  w.commit();
}

}  // namespace wr
