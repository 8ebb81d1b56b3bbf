#pragma once
// Thin RAII wrapper over FFTW's real <-> half-complex transforms on a row-major ny x nx grid.
//
// Planning (FftPlanning): `estimate` (the default) plans without timing, so the same input gives
// bit-identical output on every run. `measure` times candidate algorithms (FFTW_MEASURE; 40 %
// faster transforms at 1024^2 on 2 cores) and keeps the winners in a wisdom file
// (fft_wisdom_path()), so that later runs on this machine reuse the same plans: their output is
// then identical from run to run too, and the planning cost (about 1 s per size) is paid once.
// Measuring overwrites the arrays: a measured plan must be made before its data is written.
// Unnormalised, as FFTW:
// forward X[k] = sum_n x[n] e^{-i k.n}, backward x[n] = sum_k X[k] e^{+i k.n}.
#include <complex>
#include <cstddef>
#include <string>

#include <fftw3.h>

namespace wr {

// Hardware threads of this machine (at least 1): the default FFT thread count.
int hardware_threads();

enum class FftPlanning { estimate, measure };
// `destroy`: forward() may overwrite real() (FFTW_DESTROY_INPUT), which lets FFTW pick faster
// plans (a 2048^2 single-precision pair: 15-20 % faster on 2 cores) for transforms whose real
// array is rewritten by backward() anyway, as in a convolution in place.
// `in_place`: the spectrum overwrites the real array itself, whose rows are then padded to
// row_stride() = 2 (nx/2 + 1) values (FFTW's in-place layout; the padding holds no data and
// backward() leaves it undefined). A 2048^2 pair is another ~30 % faster (single precision,
// 2 cores): no separate spectrum buffer to stream.
enum class FftInput { preserve, destroy, in_place };

// The wisdom file of measured plans: $WETROAD_FFT_WISDOM, else $XDG_CACHE_HOME/wetroad/fftw-wisdom,
// else $HOME/.cache/wetroad/fftw-wisdom ("" when none can be named); single-precision plans are
// kept beside it, in the same name with "-single" appended. A cache: when it cannot be read or
// written, plans are measured again and nothing fails.
std::string fft_wisdom_path();

// FFTW's double (fftw_*) and single (fftwf_*) precision interfaces behind one name each
// (fft.cpp); the plan types are needed here.
template <class Real>
struct FftwApi;
template <class Real>
struct FftwPlanType;
template <>
struct FftwPlanType<double> {
  using type = fftw_plan;
};
template <>
struct FftwPlanType<float> {
  using type = fftwf_plan;
};

// Real is double or float (single precision: half the memory traffic, about 0.6x the time of a
// double transform at 2048^2; for operators that tolerate 1e-7 relative rounding, such as a
// preconditioner).
template <class Real>
class BasicRealFft2d {
 public:
  // ny == 1 gives a 1-D transform of length nx. threads <= 0: hardware_threads().
  // `external_real` (ny * row_stride() values, owned by the caller and alive as long as this object) is
  // used as the real array instead of an internal one: it saves a copy and, more importantly
  // on virtual machines, the first-touch page faults of a second large buffer. forward()
  // leaves it intact unless `input` allows otherwise (FftInput).
  BasicRealFft2d(std::size_t nx, std::size_t ny, int threads = 0, Real* external_real = nullptr,
                 FftPlanning planning = FftPlanning::estimate, FftInput input = FftInput::preserve);
  ~BasicRealFft2d();
  BasicRealFft2d(const BasicRealFft2d&) = delete;
  BasicRealFft2d& operator=(const BasicRealFft2d&) = delete;

  std::size_t nx() const { return nx_; }
  std::size_t ny() const { return ny_; }
  std::size_t nxh() const { return nx_ / 2 + 1; }  // stored columns of the half spectrum
  // Values per row of real(): nx, or 2 nxh for FftInput::in_place.
  std::size_t row_stride() const { return in_place_ ? 2 * nxh() : nx_; }

  Real* real() { return real_; }                          // ny rows of row_stride()
  std::complex<Real>* spectrum() { return spec_; }        // ny*nxh, row-major
  void forward();   // real() -> spectrum(); real() is kept unless planned with FftInput::destroy
  // in (laid out as real(), left intact) -> spectrum(), without copying it into real() when
  // its alignment allows FFTW to use the same plan (always true for two BigVector arrays) and
  // the plan preserves its input.
  void forward_from(const Real* in);
  void backward();  // spectrum() -> real() (destroys spectrum())

 private:
  using Plan = typename FftwPlanType<Real>::type;
  std::size_t nx_, ny_;
  Real* real_ = nullptr;
  bool owns_real_ = true;
  bool destroys_input_ = false;
  bool in_place_ = false;
  std::complex<Real>* spec_ = nullptr;
  Plan fwd_ = nullptr;
  Plan bwd_ = nullptr;
};

using RealFft2d = BasicRealFft2d<double>;
using RealFft2dSingle = BasicRealFft2d<float>;

}  // namespace wr
