#include "lib/spectral/traction_response.hpp"

#include <algorithm>
#include <complex>
#include <numbers>
#include <stdexcept>

namespace wr {

TractionResponse::TractionResponse(std::size_t nx, std::size_t ny, double lx, double ly, const ElasticBody& body,
                                   int threads, FftPlanning planning)
    : nx_(nx), ny_(ny), n_(nx * ny), mean_(shear_compliance_mean(body)) {
  check_body(body);
  if (body.half_space())
    throw std::invalid_argument("tangential loading needs a layer of finite thickness (the half-space's mean shear "
                                "compliance is unbounded)");
  fx_ = std::make_unique<RealFft2d>(nx, ny, threads, nullptr, planning);
  fy_ = std::make_unique<RealFft2d>(nx, ny, threads, nullptr, planning);
  fp_ = std::make_unique<RealFft2d>(nx, ny, threads, nullptr, planning);
  const std::size_t nxh = fx_->nxh();
  c_.resize(ny * nxh);
  const double qx0 = 2 * std::numbers::pi / lx, qy0 = 2 * std::numbers::pi / ly;
  for (std::size_t j = 0; j < ny; ++j) {
    const double ky = qy0 * (j <= ny / 2 ? double(j) : double(j) - double(ny));
    for (std::size_t i = 0; i < nxh; ++i) {
      TangentialCompliance c = tangential_compliance(body, qx0 * double(i), ky);
      // An operator odd in q_x (q_y) has no real representation at the Nyquist wavenumber of x (y).
      if (2 * i == nx) c.cxz = c.cxy = 0;
      if (2 * j == ny) c.cyz = c.cxy = 0;
      c_[j * nxh + i] = c;
    }
  }
}

void TractionResponse::apply(std::span<const double> tx, std::span<const double> ty, std::span<const double> p,
                             double far_x, double far_y, std::vector<double>& ux, std::vector<double>& uy,
                             std::vector<double>& uz) {
  std::copy(tx.begin(), tx.end(), fx_->real());
  std::copy(ty.begin(), ty.end(), fy_->real());
  std::copy(p.begin(), p.end(), fp_->real());
  fx_->forward();
  fy_->forward();
  fp_->forward();
  const std::size_t m = ny_ * fx_->nxh();
  std::complex<double>*sx = fx_->spectrum(), *sy = fy_->spectrum(), *sp = fp_->spectrum();
  const std::complex<double> I(0, 1);
  const double inv_n = 1.0 / double(n_);
  const std::complex<double> mean_x = sx[0], mean_y = sy[0];
  for (std::size_t k = 0; k < m; ++k) {
    const TangentialCompliance& c = c_[k];
    const std::complex<double> a = sx[k], b = sy[k], q = sp[k];
    sx[k] = (c.cxx * a + c.cxy * b + I * c.cxz * q) * inv_n;
    sy[k] = (c.cxy * a + c.cyy * b + I * c.cyz * q) * inv_n;
    sp[k] = (-I * c.cxz * a - I * c.cyz * b) * inv_n;
  }
  // Mean modes: the far face's rigid displacement plus the layer's simple shear.
  sx[0] = far_x + mean_ * mean_x.real() * inv_n;
  sy[0] = far_y + mean_ * mean_y.real() * inv_n;
  sp[0] = 0;
  fx_->backward();
  fy_->backward();
  fp_->backward();
  ux.assign(fx_->real(), fx_->real() + n_);
  uy.assign(fy_->real(), fy_->real() + n_);
  uz.assign(fp_->real(), fp_->real() + n_);
}

}  // namespace wr
