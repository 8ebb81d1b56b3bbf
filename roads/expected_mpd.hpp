#pragma once
// MPD expected on standard-length (>= 100 mm) profiles drawn from a prescribed isotropic PSD,
// for synthesized tiles that are shorter than the ISO baseline.
//
// Long-wavelength assumption: the PSD plateau k continues below qL down to q = 0 (the
// self-affine spectrum rolls off to a constant at long wavelengths, eq. 3.85 with qL -> 0),
// i.e. the road carries no extra megatexture or unevenness beyond the sample's plateau.
// The 1-D profile PSD is C1(qx) = integral over qy of C(sqrt(qx^2 + qy^2)) (isotropy); random-
// phase profiles of `profiles` x `length` metres are synthesized from it by FFT and measured
// with the same ISO 13473-1 pipeline as real data (mpd.hpp).
#include <cstdint>

#include "roads/mpd.hpp"
#include "roads/self_affine_psd.hpp"

namespace wr {

struct ExpectedMpdOptions {
  int profiles = 4;
  double length = 5.0;         // m per profile (50 segments of 100 mm)
  double min_spacing = 5e-5;   // m; finer sampling adds nothing after the 0.5 mm resampling
  std::uint64_t seed = 12345;
  MpdOptions mpd;
};

struct ExpectedMpd {
  double mpd = 0;       // m
  double mpd_std = 0;   // m, spread of segment depths
  double std_error = 0; // m, standard error of the mean
  std::size_t segments = 0;
  double spacing = 0;   // m
  std::string assumption;
};

// 1-D profile PSD of an isotropic 2-D PSD (m^3), by Gauss-Legendre quadrature over qy.
double profile_psd(const SelfAffinePsd& psd, double qx);

ExpectedMpd expected_mpd(const SelfAffinePsd& psd, double surface_dx, const ExpectedMpdOptions& opt = {});

}  // namespace wr
