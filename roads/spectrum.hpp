#pragma once
// Power spectrum of a height map and its moments (thesis sec. 3.1.2, 3.2.3).
//
// Maps: with the DFT h = sum_q B_q e^{i q.x} on the lattice q = (m qLx, n qLy), the 2-D PSD is
// C(q) = |B_q|^2 / (qLx qLy) (eq. 3.89, design.md), and the isotropic moments are the lattice
// sums m0 = sum |B|^2, m2 = sum |B|^2 |q|^2 / 2, m4 = sum |B|^2 3|q|^4 / 8 (the ring integrals of
// eq. 3.18-3.20 written over the q-plane). So sqrt(2 m2) is exactly the rms of the spectral
// gradient, whatever the direction of the waves.
// Radial average (eq. 3.91-3.92): each coefficient goes to the bin m = round(|q| / dq),
// dq = min(qLx, qLy); C of a bin is the mean over its coefficients.
//
// Profiles (ny == 1): the 1-D PSD C1(q) = |B_q|^2 / qL (so h0^2 = integral of C1 over all q),
// and m0 = sum |B|^2, m2 = sum |B|^2 q^2, m4 = sum |B|^2 q^4: for an isotropic surface these are
// the surface's own m0, m2, m4 (eq. 3.14-3.17), which is why a profile gives alpha.
#include <cstddef>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

struct RadialPsd {
  std::vector<double> q;      // 1/m, bin centres m*dq
  std::vector<double> C;      // m^4 (maps) or m^3 (profiles)
  std::vector<double> count;  // coefficients averaged into the bin
};

struct SpectralMoments {
  double m0 = 0, m2 = 0, m4 = 0;
  double alpha() const { return m0 * m4 / (m2 * m2); }
};

struct SpectrumResult {
  RadialPsd psd;
  SpectralMoments moments;
  double nyquist = 0;  // 1/m, pi / max(dx, dy): the largest wavenumber resolved in every direction
};

SpectrumResult analyze_spectrum(const HeightMap& map, int threads = 0);

}  // namespace wr
