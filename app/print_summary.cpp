#include "app/print_summary.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

namespace wr::app {
namespace {

std::string cell(const std::optional<double>& v, const char* f = "%.4g") {
  if (!v || !std::isfinite(*v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, *v);
  return b;
}

void row(std::string& out, const char* name, const std::optional<double>& measured,
         const std::optional<double>& prescribed, const char* unit, bool show_prescribed) {
  char b[256];
  if (show_prescribed)
    std::snprintf(b, sizeof b, "  %-28s %14s %14s  %s\n", name, cell(measured).c_str(), cell(prescribed).c_str(), unit);
  else
    std::snprintf(b, sizeof b, "  %-28s %14s  %s\n", name, cell(measured).c_str(), unit);
  out += b;
}

}  // namespace

std::string format_analysis(const AnalysisReport& r) {
  std::string out;
  char b[512];
  const bool pre = r.synthesis.has_value();
  const auto& p = r.prescribed;
  std::snprintf(b, sizeof b, "%s (%s %s%s)\n", r.source.c_str(), r.format.c_str(), r.profile ? "profile" : "map",
                r.periodic ? ", periodic" : "");
  out += b;
  if (r.profile)
    std::snprintf(b, sizeof b, "  %zu samples, dx = %.4g m, length %.4g m\n", r.nx, r.dx, r.nx * r.dx);
  else
    std::snprintf(b, sizeof b, "  %zu x %zu samples (x by y), dx = %.4g m, dy = %.4g m, extent %.4g x %.4g m\n",
                  r.nx, r.ny, r.dx, r.dy, r.nx * r.dx, r.ny * r.dy);
  out += b;
  std::snprintf(b, sizeof b, "  dropouts filled: %zu; mean plane removed: offset %.4g m, tilt %.3g (x), %.3g (y)\n",
                r.dropouts, r.offset, r.tilt_x, r.tilt_y);
  out += b;
  if (pre) {
    const auto& s = *r.synthesis;
    std::snprintf(b, sizeof b,
                  "  synthesized: seed %llu, q1 %.4g 1/m cut at %.4g, eq. 4.4 alone would give h0 %+.3f%%\n",
                  static_cast<unsigned long long>(s.seed), s.psd.q1, s.psd.q1_cut,
                  100 * (s.h0_eq44_on_lattice / s.psd.h0 - 1));
    out += b;
    std::snprintf(b, sizeof b, "\n  %-28s %14s %14s  %s\n", "quantity", "measured", "prescribed", "unit");
  } else {
    std::snprintf(b, sizeof b, "\n  %-28s %14s  %s\n", "quantity", "measured", "unit");
  }
  out += b;
  row(out, "h0 (Sq)", r.h0, p.h0, "m", pre);
  row(out, "Sa", r.sa, std::nullopt, "m", pre);
  row(out, "Ssk", r.ssk, std::nullopt, "", pre);
  row(out, "Sku", r.sku, std::nullopt, "", pre);
  row(out, "rms slope, spectral", r.rms_slope_spectral, p.rms_slope_spectral, "sqrt(2 m2)", pre);
  row(out, "rms slope, finite diff.", r.rms_slope_fd, std::nullopt, "forward differences", pre);
  row(out, "rms slope, central diff.", r.rms_slope_central, std::nullopt, "central, as gradient()", pre);
  row(out, "m0", r.moments.m0, p.m0, "m^2", pre);
  row(out, "m2", r.moments.m2, p.m2, "", pre);
  row(out, "m4", r.moments.m4, p.m4, "1/m^2", pre);
  row(out, "alpha = m0 m4 / m2^2", r.moments.alpha(), p.alpha, "", pre);
  const auto fit = [&](double v) { return r.fit.ok ? std::optional<double>(v) : std::nullopt; };
  row(out, "Hurst exponent (fit)", fit(r.fit.hurst), p.hurst, "", pre);
  row(out, "roll-off q0 (fit)", fit(r.fit.q0), p.q0, "1/m", pre);
  row(out, "plateau k (fit)", fit(r.fit.plateau_k), p.plateau, r.profile ? "m^3 (1-D PSD)" : "m^4", pre);
  std::snprintf(b, sizeof b, "  %-28s %14s  R^2 %.4f, rms %.3f decades, %zu bins %.3g..%.3g 1/m%s%s\n", "  fit quality",
                "", r.fit.r2, r.fit.rms_log10, r.fit.bins, r.fit.q_min, r.fit.q_max, r.fit.note.empty() ? "" : "; ",
                r.fit.note.c_str());
  out += b;
  if (!r.profile) {
    row(out, "summit density", r.summit_density, p.summit_density, "1/m^2 (Nayak eq. 3.67)", pre);
    row(out, "summit mean height", r.summit_mean, p.summit_mean, "h0 (eq. 4.5)", pre);
    row(out, "summit height variance", r.summit_var, p.summit_var, "h0^2 (eq. 4.5)", pre);
    std::snprintf(b, sizeof b,
                  "    %zu summits; at the measured alpha Nayak gives density %s, mean %s, var %s; "
                  "KS distance %s\n",
                  r.summit_count.value_or(0), cell(r.nayak_density).c_str(), cell(r.nayak_mean).c_str(),
                  cell(r.nayak_var).c_str(), cell(r.summit_ks, "%.3f").c_str());
    out += b;
  }
  row(out, "MPD", r.mpd.mpd, p.mpd, "m", pre);
  row(out, "MPD std (segments)", r.mpd.mpd_std, p.mpd_std, "m", pre);
  row(out, "ETD = 0.2 mm + 0.8 MPD", estimated_texture_depth(r.mpd.mpd), p.etd, "m", pre);
  std::snprintf(b, sizeof b,
                "    along x %s m, along y %s m; %zu profiles at %.2g mm, %zu/%zu valid segments of %.1f mm, %zu spike "
                "samples%s%s\n",
                cell(r.mpd.mpd_x).c_str(), cell(r.mpd.mpd_y).c_str(), r.mpd.profiles, r.mpd.spacing * 1e3,
                r.mpd.valid_segments, r.mpd.segments, r.mpd.baseline_used * 1e3, r.mpd.spikes,
                r.mpd.note.empty() ? "" : "\n    ", r.mpd.note.empty() ? "" : ("FLAG: " + r.mpd.note).c_str());
  out += b;
  if (!r.mpd.evaluations.empty()) {
    const auto& m = r.mpd;
    std::size_t partial = 0, invalid = 0;
    for (const EvaluationMpd& e : m.evaluations) partial += !e.complete, invalid += e.complete && !e.valid;
    std::snprintf(b, sizeof b,
                  "    per %.4g m evaluation length (ISO 13473-1 continuous record): %zu valid of %zu complete%s, MPD "
                  "mean %s m, min %s m, max %s m\n",
                  m.evaluation_length, m.evaluations_counted, m.evaluations_counted + invalid,
                  partial ? (" (+" + std::to_string(partial) + " shorter at the end, not counted)").c_str() : "",
                  cell(m.evaluation_mean).c_str(), cell(m.evaluation_min).c_str(), cell(m.evaluation_max).c_str());
    out += b;
    // A short record gets its table here; a long one's is in --json and --out (one row per length).
    if (m.evaluations.size() <= 12) {
      for (const EvaluationMpd& e : m.evaluations) {
        std::snprintf(b, sizeof b, "      %10.4g - %-10.4g m  MPD %10s m  %zu/%zu valid segments%s\n", e.start,
                      e.start + e.length, cell(e.mpd).c_str(), e.valid_segments, e.segments,
                      !e.complete ? ", shorter" : !e.valid ? ", INVALID (clause 7.10)" : "");
        out += b;
      }
    } else {
      out += "      (the table of every evaluation length: --json mpd_evaluation, --out /mpd_evaluation)\n";
    }
  }
  if (r.expected_mpd) {
    std::snprintf(b, sizeof b, "    prescribed MPD: on %zu standard 100 mm segments (+- %.2g m); %s\n",
                  r.expected_mpd->segments, r.expected_mpd->std_error, r.expected_mpd->assumption.c_str());
    out += b;
  }
  std::snprintf(b, sizeof b, "\n  contact at low pressure: kappa Persson %.4f, BGT %.4f (A/A0 = kappa sigma*)\n",
                r.kappa_persson, r.kappa_bgt);
  out += b;
  out += "  Persson A/A0 = erf(sqrt(2) sigma*):";
  for (const auto& [s, a] : r.persson_area) {
    std::snprintf(b, sizeof b, "  %.2g -> %.4f", s, a);
    out += b;
  }
  out += "\n";
  return out;
}

void print_load_warnings(const LoadedSurface& s) {
  for (const auto& w : s.warnings) std::fprintf(stderr, "wetroad: warning: %s: %s\n", s.source.c_str(), w.c_str());
}

void print_import(const LoadedSurface& s) { std::printf("read %s\n  %s\n", s.source.c_str(), describe_import(s).c_str()); }

}  // namespace wr::app
