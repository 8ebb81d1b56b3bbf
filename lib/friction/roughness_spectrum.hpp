#pragma once
// The isotropic power spectrum a sliding rubber feels, C(q) on [qs, q1], built from a measured
// radial PSD (roads/spectrum) and, beyond the map's resolution, extended along the fitted
// self-affine law (roads/psd_fit) up to the cut-off q1.
//
// Convention: h0^2 = int d^2q C(q) (design.md), C in m^4, q in 1/m.
// Measured nodes: the radial PSD's bins averaged over cells of 1/kLogBinsPerDecade decade
// (weighted by their coefficient counts), so that the high-q bins' scatter does not enter as
// kinks. Between measured nodes C is interpolated linearly in log q - log C. Above the last measured
// node q_m, C(q) = C_fit(q_m) (q/q_m)^-beta with the fitted exponent beta = 2(H+1) and the fitted
// law's value at q_m (the last bin alone is the noisiest), times `extension_scale` (a wet
// surface's flat water adds no short-wavelength roughness: its extension is the dry one times
// the dry area fraction). Every value is multiplied by `scale` (the local sealing model's
// roughness per unit dry area).
#include <optional>
#include <string>
#include <vector>

#include "roads/psd_fit.hpp"
#include "roads/spectrum.hpp"

namespace wr {

// Default cut-off: q1 = 2 pi / 20 um (3.1e5 1/m), or the map's last resolved wavenumber when it
// resolves finer. Measured road maps resolve ~0.1 mm; the rubber feels shorter wavelengths, down
// to the scale where the road's micro-texture is worn and contaminated and the tread's filler
// particles (~10-30 um) set the rubber's own smallest scale (Persson's road spectra run to
// 1e5-1e6 1/m). The user sees how much the extrapolated band carries (mu against q1).
constexpr double kDefaultQ1 = 2 * 3.14159265358979323846 / 20e-6;  // 1/m
constexpr double kLogBinsPerDecade = 20;

struct RoughnessSpectrum {
  std::vector<double> q, C;      // measured nodes, ascending, q > 0, C > 0
  double q_start = 0;            // 1/m, lower end of the friction integral (the map's qL)
  double q_end = 0;              // 1/m, q1
  double q_measured = 0;         // 1/m, last measured node
  double extension_beta = 0;     // C ~ q^-beta above q_measured
  double extension_anchor = 0;   // m^4, C of the extension at q_measured
  double extension_scale = 1;
  double scale = 1;
  bool extrapolated() const { return q_end > q_measured * (1 + 1e-12); }
  double operator()(double q) const;  // m^4; 0 outside [q_start, q_end]
  // int d^2q C over [q_start, q_end] = 2 pi int q C dq (trapezoid in ln q on the nodes): h0^2, m^2.
  double rms_height() const;
};

// From a map's radial PSD: nodes are the bins with count > 0, 0 < q <= nyquist and C > 0.
// `q1` (1/m): the cut-off; absent = max(kDefaultQ1, the last node). A q1 above the
// measured band needs a successful fit (InputError naming `source` otherwise); a q1 at or below
// the second node is refused (InputError naming --q1) as is one that is not finite.
RoughnessSpectrum spectrum_from_psd(const RadialPsd& psd, double nyquist, const PsdFit& fit,
                                    std::optional<double> q1, const std::string& source);

// A spectrum with the extension of `dry` (same beta and anchor, scaled by `extension_scale`)
// but the measured nodes of `wet_psd`: the sealed (homogeneous) wet surface.
RoughnessSpectrum wet_spectrum(const RoughnessSpectrum& dry, const RadialPsd& wet_psd, double nyquist,
                               double extension_scale);

// The cut-off by the rms-slope criterion (Lorenz, Oh, Lee, Lee & Persson, J. Chem. Phys. 142,
// 194701 (2015): the rubber feels the road down to the scale at which the surface, including the
// band extrapolated along the fitted self-affine law, reaches an rms slope of order 1; 1.3 for
// asphalt): the q1 at which sqrt(2 pi int_{qs}^{q1} q^3 C dq) = `slope` (the design's rms slope
// sqrt(2 m2)). InputError naming `option` when the slope is not reached below 1e9 1/m or the
// measured band has no fitted law to extrapolate (`source` names the surface).
constexpr double kDefaultQ1Slope = 1.3;
double q1_for_rms_slope(const RadialPsd& psd, double nyquist, const PsdFit& fit, double slope, const std::string& source,
                        const std::string& option);

// C = c (m^4) on [qa, qb] and 0 elsewhere: the one-band surface of the exact tests.
RoughnessSpectrum band_spectrum(double qa, double qb, double c);

}  // namespace wr
