#pragma once
// Squeeze-out of a water film from under a tread element pressed onto a rough road (Lorenz &
// Persson, Eur. Phys. J. E 32, 281 (2010), "Time-dependent fluid squeeze-out between solids
// with rough surfaces"; Moore's three zones: a film, a transition where it drains, a drained zone).
//
// A rib of width L (the drainage length: the water leaves across it, on both sides, into the
// grooves or out of the patch) is pressed with the nominal pressure sigma0 onto the road under a
// film. The mean separation u is the same over the rib (the rubber block is stiff on the scale
// of the rib), the asperities carry p_c(u) and the water the rest. Reynolds' equation across the
// rib with the interface's flow conductance K(u) (lib/flow): volume conservation du/dt = -dJ/dx,
// J = -(K/eta) dp_f/dx, p_f = 0 at the rib's edges, gives p_f(x) = -(eta du/dt / 2K)(L^2/4 - x^2),
// whose mean is -eta (du/dt) L^2 / (12 K); the load balance sigma0 = p_c(u) + <p_f> then gives
//     du/dt = -12 K(u) (sigma0 - p_c(u)) / (eta L^2)                                  (1)
// (Lorenz & Persson's eq. 4-6 for a strip). Smooth plates, K = u^3/12, p_c = 0:
//     t(u) = eta L^2 / (2 sigma0) (1/u^2 - 1/u0^2),
// Reynolds' squeeze film (the test's closed form). Equation (1) is integrated exactly as
// t(u) = int_u^u0 eta L^2 du' / (12 K (sigma0 - p_c)): first over the separations where the
// asperities carry nothing (trapezoid in ln u), then over the asperity pressure p_c, in ln p_c up
// to sigma0/2 and in ln(sigma0 - p_c) beyond (the approach to equilibrium is logarithmic in time).
// Where K = 0 (the free area stops percolating) the water is trapped and the history ends.
// Units: SI (m, Pa, Pa s, s, m^3).
#include <functional>
#include <vector>

namespace wr {

// The interface as the squeeze-out sees it.
struct SqueezeLaw {
  std::function<double(double)> separation;               // u(p_c), m, decreasing; p_c > 0
  std::function<double(double)> contact;                  // A/A0 at p_c
  std::function<double(double, double)> conductance;      // K(u, A), m^3
};

struct SqueezeSetup {
  double pressure = 0.3e6;        // sigma0, Pa > 0
  double viscosity = 1.0e-3;      // eta, Pa s > 0
  double drainage_length = 0.02;  // L, m > 0
  double initial_separation = 0;  // u0, m > 0 (the film's volume per unit area)
};

struct SqueezeState {
  double t = 0, separation = 0, asperity_pressure = 0, contact = 0;
};

class SqueezeHistory {
 public:
  SqueezeHistory(const SqueezeLaw& law, const SqueezeSetup& setup);
  // The state at time t >= 0 (s) after the element met the film (linear in t between nodes;
  // after the last node the last state, which is the equilibrium or the trapped state).
  SqueezeState at(double t) const;
  // Time-averages over [0, T] (T > 0): the asperities' load share <p_c / sigma0>, and
  // <(1 - A) / u> (1/m), the viscous shear's factor (the film shears at eta v / u).
  double mean_load_share(double T) const;
  double mean_inverse_film(double T) const;
  // The first time the asperities carry `share` of sigma0 (s); +inf when never reached.
  double time_to_share(double share) const;
  bool trapped() const { return trapped_; }  // the water stopped flowing before equilibrium
  const std::vector<SqueezeState>& nodes() const { return nodes_; }

 private:
  double cumulative(const std::vector<double>& integral, const std::vector<double>& value, double T) const;
  std::vector<SqueezeState> nodes_;
  std::vector<double> share_int_, film_int_;  // int_0^{t_k} of the two integrands
  std::vector<double> share_, film_;
  double pressure_ = 0;
  bool trapped_ = false;
};

// Reynolds' squeeze film between smooth plates (strip of width L): the time from u0 to u.
double smooth_plates_squeeze_time(double viscosity, double drainage_length, double pressure, double u0, double u);

}  // namespace wr
