#pragma once
// Fit of the self-affine model (eq. 3.85) to a radially averaged PSD: plateau k, roll-off q0,
// decay exponent beta (C ~ q^-beta above q0) and from it the Hurst exponent
// (maps: beta = 2(H+1); profiles: beta = 2H+1).
//
// Method: least squares in log-log space, each bin weighted by the number of coefficients it
// averages (the relative scatter of a bin mean falls like 1/sqrt(count)); the model
// log C = a - beta max(0, log(q/q0)) is linear in (a, beta) for fixed q0, so q0 is found by a
// scan over the bin positions refined by golden-section search; each trial knee costs O(log n)
// (suffix sums, psd_fit.cpp), the whole fit O(n) in the number of bins. Bins above Nyquist (incomplete
// rings) and bins where the spectrum has been cut off (power below 1e-8 of the peak from there to
// the end, plus the partially cut bin before them) are left out.
#include "roads/spectrum.hpp"

namespace wr {

struct PsdFit {
  bool ok = false;
  double plateau_k = 0;   // m^4 (maps) or m^3 (profiles)
  double q0 = 0;          // 1/m
  double beta = 0;        // decay exponent
  double hurst = 0;
  double r2 = 0;          // coefficient of determination in log space (weighted)
  double rms_log10 = 0;   // weighted rms residual, decades
  double q_min = 0, q_max = 0;  // 1/m, fitted range
  std::size_t bins = 0;
  std::string note;       // why the fit failed or what limits it
};

PsdFit fit_self_affine(const RadialPsd& psd, double nyquist, bool profile);

}  // namespace wr
