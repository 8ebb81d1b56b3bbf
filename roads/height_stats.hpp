#pragma once
// Areal height parameters (ISO 25178 names) and the finite-difference rms slope.
#include "lib/core/height_map.hpp"

namespace wr {

struct HeightStats {
  double sq = 0;   // m, rms height h0 about the mean
  double sa = 0;   // m, mean absolute height
  double ssk = 0;  // skewness
  double sku = 0;  // kurtosis (3 for a Gaussian)
  double mean = 0; // m (zero after mean-plane removal)
};

// threads <= 0: all hardware threads; results do not depend on the thread count.
HeightStats height_stats(const HeightMap& map, int threads = 0);

// Which differences estimate the slope. Forward, (h[i+1]-h[i])/dx: the slope of the
// piecewise-linear (triangulated) obstacle a contact solver meets; wetroad's sigma* uses it.
// Central, (h[i+1]-h[i-1])/(2 dx): what gradient routines (MATLAB's and NumPy's `gradient`)
// return; it damps the shortest waves (a wave q by sin(q dx)/(q dx), zero at the Nyquist
// wavenumber), so on a self-affine surface sampled to its cut-off it is ~15 % lower.
enum class SlopeStencil { forward, central };

// rms of |grad h| from finite differences along x and y. Wraps around on periodic maps;
// otherwise uses the interior differences only. For a profile: sqrt(2) times the rms of the
// profile slope, i.e. the surface rms slope assuming isotropy (comparable with sqrt(2 m2)).
double rms_slope_finite_difference(const HeightMap& map, int threads = 0,
                                   SlopeStencil stencil = SlopeStencil::forward);

}  // namespace wr
