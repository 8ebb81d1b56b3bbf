#pragma once
// Flash temperature of rubber sliding on a rough surface (after Persson, J. Phys.: Condens.
// Matter 18, 7789 (2006)): the energy dissipated at the coarser scales heats the rubber that the
// finer asperities then excite, and the warmer rubber (WLF) is softer and less lossy at a given
// frequency.
//
// Model (derivation and its assumptions in docs/friction-model.md):
//  - the power the band dq' of the spectrum dissipates per unit nominal area is sigma0 v dmu;
//    it is released in the real contact, the fraction P(q') of the area, within a depth 1/q'
//    of the surface: a heat source of density Q(q') = sigma0 v q' (dmu/dq') / P(q') ... per
//    unit volume of contact rubber, i.e. (v/2) q'^4 C(q') int cos(phi) Im E dphi / (1 - nu^2);
//  - the source acts for the time the rubber takes to slide over a contact patch of that scale,
//    t' = d'/v with d' = pi/q' (half a wavelength), decaying with depth as exp(-q' z) and
//    cooled laterally over the patch (lateral wavenumber kappa' = 2/d'), below an insulated
//    surface (the road is far less conductive per contact than the rubber bulk is thick);
//  - T_q = T0 + int_{qs}^{q} dq' Q(q') H(q', kappa', t') / (rho c): the rubber at scale q
//    carries the rise of every coarser scale (Persson's "temperature at magnification zeta").
// The response H of a source exp(-b z) switched on for a time t (units s; D = lambda/(rho c)):
//   H = (1/pi) int_0^inf dk [2b/(k^2+b^2)] [1 - exp(-D (k^2+kappa^2) t)] / (D (k^2+kappa^2))
//     = (1/D) { 1/(kappa (b+kappa)) - b/(b^2-kappa^2) [erfc(kappa sqrt(Dt))/kappa
//                                                   - exp(-D kappa^2 t) erfcx(b sqrt(Dt))/b] },
// with the limits H -> t (adiabatic, b^2 D t << 1) and H -> 1/(D kappa (b + kappa)) (steady).
#include "lib/friction/compound.hpp"

namespace wr {

// H above, s. b, kappa > 0, b != kappa; D > 0 (m^2/s); t >= 0 (s).
double flash_kernel(double b, double kappa, double diffusivity, double t);
// exp(x^2) erfc(x) without overflow, x >= 0.
double erfcx(double x);

class FlashTemperature {
 public:
  // InputError naming --flash-temperature when the compound has no thermal data.
  FlashTemperature(const Compound& compound, double v, double pressure);
  // The rise's density in ln q at node q (K per unit ln q), from the node's friction density
  // dmu/d(ln q) divided by P(q) (the heat goes into the real contact).
  double rise_density(double q, double dmu_dlnq_over_p) const;

 private:
  double v_ = 0, pressure_ = 0, rho_c_ = 0, diffusivity_ = 0;
};

}  // namespace wr
