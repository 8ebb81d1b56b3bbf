#pragma once
// Surface displacements of the periodic elastic body (surface_compliance.hpp) under the full
// traction field on its face: the tangential displacements from tangential and normal
// tractions, and the normal displacement caused by the tangential tractions (the (1 - 2 nu)
// coupling of Boussinesq-Cerruti). The normal displacement from the normal pressure is the
// normal solver's (normal_contact.hpp). Tractions in Pa on the grid of the obstacle, row-major;
// displacements in m. The mean (q = 0) tangential mode is the layer's simple shear (t / G x the
// mean traction) on top of a prescribed rigid displacement of the far face; the half-space has
// no finite mean mode and is refused.
#include <memory>
#include <span>
#include <vector>

#include "lib/core/fft.hpp"
#include "lib/spectral/surface_compliance.hpp"

namespace wr {

class TractionResponse {
 public:
  // Throws std::invalid_argument for a half-space.
  TractionResponse(std::size_t nx, std::size_t ny, double lx, double ly, const ElasticBody& body, int threads = 0,
                   FftPlanning planning = FftPlanning::measure);

  // ux, uy = (far_x, far_y) + the tangential displacements of the face; uz_coupling = the
  // normal displacement (into the body) caused by tx, ty.
  void apply(std::span<const double> tx, std::span<const double> ty, std::span<const double> p, double far_x,
             double far_y, std::vector<double>& ux, std::vector<double>& uy, std::vector<double>& uz_coupling);

 private:
  std::size_t nx_, ny_, n_;
  std::vector<TangentialCompliance> c_;  // half spectrum
  double mean_;                          // t / G
  std::unique_ptr<RealFft2d> fx_, fy_, fp_;
};

}  // namespace wr
