#pragma once
// Frictionless, non-adhesive normal contact of a periodic elastic body (half-space or layer,
// surface_compliance.hpp) on a rigid periodic obstacle given as a height map: the spectral
// (FFT boundary-element) rung of the model ladder (README).
//
// Unknown: the contact pressure p >= 0 at the grid points (one per obstacle sample). The
// body's face, flat at z = 0 before loading, is pushed down by the approach d and lifted by
// its elastic displacement w = C * p (a convolution applied in Fourier space, C from
// surface_compliance.hpp); the gap to the obstacle z_o = h - max h (<= 0) is
//   g = w - d - z_o >= 0,  p >= 0,  p g = 0.
// This is the minimum of the convex energy 1/2 p.Cp - p.(d + z_o) over p >= 0, solved by the
// constrained conjugate-gradient method of Polonsky & Keer (Wear 231, 1999): CG restricted to
// the points in contact, projection onto p >= 0, re-admission of penetrating points with a
// restart of the conjugate directions. Two changes make it scale: the residual is
// preconditioned by R C^-1 R^T on the contact set (Vollebregt, JOTA 2014; exact at full
// contact), and penetrating points are admitted in batches (every `admit_every` iterations)
// so that CG keeps its directions in between. Load control (the mean pressure given, d the
// Lagrange multiplier of that constraint) works for the half-space and the layer;
// displacement control (d given) needs a bounded mean compliance, i.e. a layer.
//
// Convergence (Polonsky-Keer's criterion): the relative l1 change of the pressure in one
// iteration, sum |p_k+1 - p_k| / sum p_k+1, below `tolerance`, with no penetrating point left
// waiting for admission. The residual of the complementarity conditions is reported beside it
// (contact_gap, max_penetration). An error that stops decreasing ends the solve (stagnated).
#include <memory>
#include <string>
#include <vector>

#include "lib/core/fft.hpp"
#include "lib/core/height_map.hpp"
#include "lib/core/stagnation.hpp"
#include "lib/spectral/surface_compliance.hpp"

namespace wr {

struct SpectralOptions {
  double tolerance = 1e-8;    // relative l1 change of the pressure per iteration
  int max_iterations = 5000;  // CG iterations per solve
  std::size_t stagnation_window = 100;  // stop when the error has not halved over two windows
  int admit_every = 8;        // iterations between admissions of penetrating points (1: Polonsky-Keer)
  int threads = 0;            // FFT threads (0: all hardware threads); read where a solver is built
  FftPlanning planning = FftPlanning::measure;  // read where a solver is built (lib/core/fft.hpp)
  // Precision of the CG's residual, direction and convolution r = C t (the pressure, the
  // elastic displacement and its full recomputations stay double). Single precision halves
  // their memory traffic (2048^2: 18 % less time, same iterations) but carries the error only
  // to about 1e-10: a solve asking for less stalls in a limit cycle at 3e-11 ... 3e-10
  // (Westergaard wave, 4096 points). `automatic`: single for tolerance >= 1e-9, else double.
  enum class Precision { automatic, single, full };
  Precision precision = Precision::automatic;
  bool single_precision_cg() const {
    return precision == Precision::single || (precision == Precision::automatic && tolerance >= 1e-9);
  }
};

struct SpectralNormalResult {
  double mean_pressure = 0;   // Pa, over the nominal area
  double approach = 0;        // m, d: rigid displacement of the far face (layer) or of the
                              // mean plane (half-space, defined up to the unbounded q = 0 mode)
  double area_fraction = 0;   // points with p > 0 / all points
  double mean_gap = 0;        // m, mean of g over all points (mean separation)
  double max_penetration = 0; // m, largest -g at points without pressure (0 when none)
  double contact_gap = 0;     // m, largest |g| at points with pressure (0 at the exact solution)
  int iterations = 0;
  int fft_pairs = 0;          // convolutions done (forward + backward transform each)
  bool converged = false;
  std::string message;        // why not converged
  std::vector<double> history;  // Polonsky-Keer error per iteration
  double wall_s = 0;
};

class SpectralNormalContact {
 public:
  // `obstacle` periodic, finite heights. Throws std::invalid_argument for bad inputs.
  // `planning`: measured FFT plans (the default) are about 40 % faster and cached per machine
  // (lib/core/fft.hpp); `estimate` gives bit-identical results across machines.
  SpectralNormalContact(const HeightMap& obstacle, const ElasticBody& body, int threads = 0,
                        FftPlanning planning = FftPlanning::measure);
  ~SpectralNormalContact();
  SpectralNormalContact(const SpectralNormalContact&) = delete;
  SpectralNormalContact& operator=(const SpectralNormalContact&) = delete;

  // Load control: mean pressure (Pa, > 0). Warm-starts from the previous solution.
  SpectralNormalResult solve_load(double mean_pressure, const SpectralOptions& opt);
  // Displacement control: approach d (m, >= 0) of the fixed face; layer only.
  SpectralNormalResult solve_approach(double approach, const SpectralOptions& opt);

  // Replaces the obstacle's heights (m, same grid; measured like the original's, whose highest
  // point stays the reference z = 0 of the approach): the geometry-following shear test moves
  // the face over the obstacle and solves again. Keeps the pressure as the next start.
  void set_heights(const std::vector<double>& heights);

  const BigVector& pressure() const;  // Pa, row-major as the obstacle
  const BigVector& gap() const;       // m
  std::size_t nx() const;
  std::size_t ny() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wr
