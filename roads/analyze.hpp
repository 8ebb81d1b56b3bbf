#pragma once
// `wetroad analyze`: every statistic of a loaded surface, as one report.
//
// Life of an analysis (each phase timed): spectrum (FFT, radial PSD, moments) -> PSD fit ->
// height statistics -> summits vs Nayak -> MPD (ISO 13473-1) -> analytic contact predictions
// -> prescribed values (for synthesized files).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/core/provenance.hpp"
#include "roads/expected_mpd.hpp"
#include "roads/mpd.hpp"
#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"
#include "roads/surface_import.hpp"

namespace wr {

struct AnalysisOptions {
  int threads = 0;                 // FFT threads, 0 = hardware
  MpdOptions mpd;
  bool expected_mpd = true;        // for synthesized files (costs ~10 ms)
  std::vector<double> sigma_stars = {0.01, 0.05, 0.1, 0.2, 0.5};
};

// Values that exist both measured and prescribed share this block (the same JSON names).
struct SurfaceFigures {
  std::optional<double> h0, rms_slope_spectral, m0, m2, m4, alpha, hurst, q0, plateau,
      summit_density, summit_mean, summit_var, mpd, mpd_std, etd;
};

struct AnalysisReport {
  // Input
  std::string source, format;
  std::size_t nx = 0, ny = 0;
  double dx = 0, dy = 0;
  bool profile = false, periodic = false;
  std::size_t dropouts = 0;
  double tilt_x = 0, tilt_y = 0, offset = 0;
  // Measured
  double h0 = 0, sa = 0, ssk = 0, sku = 0;
  double rms_slope_spectral = 0, rms_slope_fd = 0, rms_slope_central = 0;  // fd: forward differences
  SpectralMoments moments;
  RadialPsd psd;
  double nyquist = 0;
  PsdFit fit;
  std::optional<std::size_t> summit_count;
  std::optional<double> summit_density, summit_mean, summit_var, summit_ks;
  std::optional<double> nayak_density, nayak_mean, nayak_var, greenwood_mean, greenwood_var;
  std::vector<double> summit_xi;
  MpdResult mpd;
  double kappa_persson = 0, kappa_bgt = 0;
  std::vector<std::pair<double, double>> persson_area;  // (sigma*, A/A0)
  // Prescribed (synthesized files)
  std::optional<SynthesisRecord> synthesis;
  SurfaceFigures prescribed;
  std::optional<ExpectedMpd> expected_mpd;
  PhaseTimer timer;

  nlohmann::json to_json() const;
};

AnalysisReport analyze_surface(const LoadedSurface& surface, const AnalysisOptions& opt = {});

// Saves the report as HDF5: attributes for the scalars, /psd/q and /psd/C, /summits/xi, and the
// JSON summary plus provenance as root attributes. Written atomically.
void write_analysis_file(const std::string& path, const AnalysisReport& r, const Provenance& prov);

}  // namespace wr
