#include "lib/core/fft.hpp"

#include "lib/core/big_buffer.hpp"

#include <mutex>
#include <new>
#include <thread>

namespace wr {

int hardware_threads() {
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

RealFft2d::RealFft2d(std::size_t nx, std::size_t ny, int threads, double* external_real) : nx_(nx), ny_(ny) {
  // FFTW keeps its thread support process-wide; initialising it twice is harmless but
  // call_once keeps it cheap.
  static std::once_flag init;
  std::call_once(init, [] { fftw_init_threads(); });
  if (threads <= 0) threads = hardware_threads();
  owns_real_ = external_real == nullptr;
  real_ = owns_real_ ? static_cast<double*>(allocate_big(nx * ny * sizeof(double))) : external_real;
  spec_ = static_cast<std::complex<double>*>(allocate_big(ny * nxh() * sizeof(std::complex<double>)));

  // Small transforms gain nothing from threads.
  fftw_plan_with_nthreads(nx * ny >= (1u << 16) ? threads : 1);
  auto* c = reinterpret_cast<fftw_complex*>(spec_);
  if (ny == 1) {
    fwd_ = fftw_plan_dft_r2c_1d(static_cast<int>(nx), real_, c, FFTW_ESTIMATE);
    bwd_ = fftw_plan_dft_c2r_1d(static_cast<int>(nx), c, real_, FFTW_ESTIMATE);
  } else {
    fwd_ = fftw_plan_dft_r2c_2d(static_cast<int>(ny), static_cast<int>(nx), real_, c, FFTW_ESTIMATE);
    bwd_ = fftw_plan_dft_c2r_2d(static_cast<int>(ny), static_cast<int>(nx), c, real_, FFTW_ESTIMATE);
  }
}

RealFft2d::~RealFft2d() {
  if (fwd_) fftw_destroy_plan(fwd_);
  if (bwd_) fftw_destroy_plan(bwd_);
  if (owns_real_) free_big(real_, nx_ * ny_ * sizeof(double));
  free_big(spec_, ny_ * nxh() * sizeof(std::complex<double>));
}

void RealFft2d::forward() { fftw_execute(fwd_); }
void RealFft2d::backward() { fftw_execute(bwd_); }

}  // namespace wr
