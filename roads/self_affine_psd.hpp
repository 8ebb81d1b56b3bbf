#pragma once
// The isotropic self-affine power spectrum of eq. 3.85 and its continuous moments.
//
// Units: wavenumbers in 1/m, C(q) in m^4 (so that h0^2 = integral of C over the q-plane, eq. 3.6).
// Contract: 0 < qL <= q0 < q1, 0 < H < 1 (a Hurst exponent outside that range is refused by
// the caller). `q1_cut` (<= q1) low-passes the spectrum without re-normalising it, as in the
// thesis's dataset C: the plateau k stays that of the full spectrum and h0 drops.
namespace wr {

struct SelfAffinePsd {
  double h0 = 0;      // m, rms height the full (uncut) spectrum is normalised to
  double hurst = 0;   // H
  double qL = 0;      // 1/m, smallest wavenumber 2 pi / L
  double q0 = 0;      // 1/m, roll-off
  double q1 = 0;      // 1/m, short-distance cut-off used for normalisation
  double q1_cut = 0;  // 1/m, effective cut-off (q1 times the low-pass fraction)
  double k = 0;       // m^4, plateau value

  // Plateau from eq. 4.4 (exact for the continuous integral of eq. 3.85 between qL and q1).
  static SelfAffinePsd from_eq44(double h0, double hurst, double qL, double q0, double q1,
                                 double q1_fraction = 1.0);

  // C(q) of eq. 3.85 with the cut at q1_cut (inclusive), m^4.
  double operator()(double q) const;

  // Continuous moments of the (cut) spectrum, eq. 3.18-3.20: m0 [m^2], m2 [-], m4 [1/m^2].
  double m0() const;
  double m2() const;
  double m4() const;
  double alpha() const { return m0() * m4() / (m2() * m2()); }
  double rms_slope() const;  // sqrt(2 m2), eq. 3.168
  double rms_height() const;  // sqrt(m0)

 private:
  // integral over [qL, q1_cut] of q^n C(q) dq
  double radial_integral(int n) const;
};

}  // namespace wr
