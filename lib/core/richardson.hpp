#pragma once
// Richardson extrapolation from three solutions on meshes refined by a constant ratio, with the
// observed order and Roache's grid-convergence index (GCI) as the error estimate.
//
// Why three: the order is not assumed but measured, from the ratio of successive differences,
// (f0 - f1) / (f1 - f2) = r^p; with two solutions the order would have to be taken on trust.
// A ratio <= 1 (differences not shrinking, or changing sign) means the meshes are not in the
// asymptotic range: no limit is claimed then.
#include <optional>

namespace wr {

struct RichardsonEstimate {
  double order = 0;  // observed order p
  double limit = 0;  // extrapolated value f2 + (f2 - f1) / (r^p - 1)
  // GCI of the finest solution, Fs |f2 - f1| / (r^p - 1) with the safety factor Fs = 1.25
  // (Roache 1998, three-grid study): the band about `limit` within which the mesh-converged
  // value is claimed to lie; same unit as f.
  double error = 0;
};

// f0, f1, f2: the quantity on the coarse, middle and fine mesh; `ratio` > 1: the spacing ratio
// between successive meshes (2 for halving). Returns nullopt outside the asymptotic range
// ((f0 - f1) / (f1 - f2) <= 1, or f1 == f2 with f0 != f1). Equal values converge at once:
// order infinite is reported as 0 with error 0.
std::optional<RichardsonEstimate> richardson_three(double f0, double f1, double f2, double ratio = 2.0);

}  // namespace wr
