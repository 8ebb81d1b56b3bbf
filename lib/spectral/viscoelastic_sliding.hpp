#pragma once
// Steady sliding of a viscoelastic half-space over a rigid periodic road map: the exact rung of
// the hysteresis friction (Persson's theory, lib/friction/hysteresis_friction.hpp, is its
// mean-field approximation). The FFT boundary-element method of the spectral model
// (normal_contact.hpp) with the rubber's complex modulus.
//
// Frame: the road's. The rubber slides along +x at speed v; in steady state its face is a
// stationary field, and a material point of the rubber meets the surface wave e^{i q.x} at the
// angular frequency omega = q_x v. So a pressure mode p_q lifts the face by
//   w_q = C(q) p_q,   C(q) = 2 (1 - nu^2) / (|q| E(q_x v, T)),   E(-omega) = conj E(omega)
// (Carbone & Putignano, J. Mech. Phys. Solids 61, 1822 (2013), eq. 8 in Fourier form; Persson,
// J. Chem. Phys. 115, 3840 (2001), eq. 4). The operator is real but not symmetric: its symmetric
// part has the symbol Re C = 2 (1 - nu^2) E' / (|q| |E|^2) > 0, so it is positive definite and
// the contact problem (gap g = w - d - z_o >= 0, p >= 0, p g = 0, mean p = sigma0) has one
// solution, but it is no energy minimum and conjugate gradients do not apply.
//
// Iteration: the Polonsky-Keer active-set scheme of normal_contact.hpp with its conjugate
// gradients replaced by truncated GCR (generalized conjugate residual, Eisenstat, Elman & Schultz,
// SIAM J. Numer. Anal. 20, 345 (1983)): on the contact set, directions minimise the residual
// of the gap in the Euclidean norm, each orthogonalised against the last `window` ones. GCR
// converges for any positive-definite operator, truncated or not (ibid., theorem 3.3); for an
// elastic (symmetric) compound it is the conjugate-residual method. The preconditioner is
// R C^-1 R^T with the viscoelastic inverse symbol (exact at full contact: one iteration), the
// projection onto p >= 0 and the re-admission of penetrating points restart the directions, and
// the mean pressure is kept by load-neutral (zero-sum) directions with the approach d as the
// multiplier of the load, as in the elastic solver.
//
// Outputs (SI): the friction coefficient as the tangential force of the pressure on the sloped
// road, mu = <p dh/dx> / sigma0 (spectral derivative), the real contact area, and the power
// dissipated in the rubber per unit nominal area P = v <p dw/dx> = v sum_q |p_q|^2 (-q_x Im C(q)),
// whose friction mu_dissipation = P / (sigma0 v) equals mu at the exact solution (the face
// follows the road where it presses: dw/dx = dh/dx there). On a grid the two differ by the
// contact edges' discretisation (sum p D(g) over the edge points), which the result reports
// as identity_residual; in full contact they agree to the solver's tolerance.
//
// Validity: small slopes (the linear half-space), no adhesion, isothermal (no flash
// temperature), sliding along x only. Units: m, Pa, m/s, deg C.
#include <memory>
#include <string>
#include <vector>

#include "lib/core/big_buffer.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/height_map.hpp"
#include "lib/friction/compound.hpp"

namespace wr {

struct SlidingOptions {
  double tolerance = 1e-8;      // relative l1 change of the pressure per iteration
  int max_iterations = 20000;   // per solve
  int window = 8;               // GCR directions kept (>= 1)
  int admit_every = 8;          // iterations between admissions of penetrating points
  std::size_t stagnation_window = 400;  // stop when the error has not halved over two windows
  int threads = 0;              // 0: all hardware threads
  FftPlanning planning = FftPlanning::estimate;
};

struct SlidingResult {
  double speed = 0;              // m/s
  double mean_pressure = 0;      // Pa
  double approach = 0;           // m, the multiplier of the load (half-space: up to a constant)
  double area_fraction = 0;      // points with p > 0 / all points
  double mu = 0;                 // <p dh/dx> / sigma0
  double mu_dissipation = 0;     // P / (sigma0 v)
  double dissipation = 0;        // W/m^2, P per unit nominal area
  double identity_residual = 0;  // |mu_dissipation - mu| / max(|mu|, |mu_dissipation|) (0 when both 0)
  double mean_gap = 0;           // m
  double max_penetration = 0;    // m, largest -g off the contact set
  double contact_gap = 0;        // m, largest |g| on the contact set
  int iterations = 0;
  int fft_pairs = 0;
  bool converged = false;
  std::string message;           // why not converged
  std::vector<double> history;   // relative l1 change per iteration
  double wall_s = 0;
};

class ViscoelasticSliding {
 public:
  // `road`: periodic, finite heights, at least 2 samples per row (a profile, ny = 1, is a
  // plane-strain problem); `temperature` in deg C above the compound's WLF pole.
  // InputError/std::invalid_argument for bad inputs.
  ViscoelasticSliding(const HeightMap& road, const Compound& compound, double temperature,
                      const SlidingOptions& opt);
  ~ViscoelasticSliding();
  ViscoelasticSliding(const ViscoelasticSliding&) = delete;
  ViscoelasticSliding& operator=(const ViscoelasticSliding&) = delete;

  // The steady state at `speed` (m/s, > 0; the compound's loss makes the answer depend on it)
  // under the mean pressure `pressure` (Pa, > 0). Starts from the previous solve's pressure
  // (a speed or load sweep), else from a uniform pressure.
  // A compound without loss (no Prony terms, or all of zero strength) is the elastic problem
  // of normal_contact.hpp.
  SlidingResult solve(double speed, double pressure);

  // The last solve's dissipation friction mu_dissipation split by |q| into the bins
  // [edges[k], edges[k+1]) (1/m, ascending): which scales of the road the rubber loses its energy on,
  // to compare with the integrand of Persson's theory.
  std::vector<double> friction_by_wavenumber(const std::vector<double>& edges);

  const BigVector& pressure() const;  // Pa, row-major as the road
  const BigVector& gap() const;       // m
  // Bytes held by the solver's arrays (grid, spectra, GCR window).
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// mu of the exact full-contact solution on h(x) = amplitude cos(q x) (rubber sliding along x):
//   mu = (q h)^2 Im E(q v) / (4 (1 - nu^2) sigma0),
// valid while sigma0 >= q h |E(q v)| / (2 (1 - nu^2)) (the pressure stays >= 0). Derivation:
// docs/friction-model.md, "The exact rung".
double sinusoid_full_contact_mu(const Compound& compound, double temperature, double wavenumber, double amplitude,
                                double speed, double pressure);

}  // namespace wr
