#include "lib/core/fft.hpp"

#include "lib/core/big_buffer.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <new>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace wr {

int hardware_threads() {
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

std::string fft_wisdom_path() {
  if (const char* f = std::getenv("WETROAD_FFT_WISDOM"); f && *f) return f;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/wetroad/fftw-wisdom";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/wetroad/fftw-wisdom";
  return "";
}

template <>
struct FftwApi<double> {
  using Plan = fftw_plan;
  using Complex = fftw_complex;
  static constexpr const char* wisdom_suffix = "";
  static void init_threads() { fftw_init_threads(); }
  static void plan_with_nthreads(int n) { fftw_plan_with_nthreads(n); }
  static Plan r2c_1d(int n, double* in, Complex* out, unsigned f) { return fftw_plan_dft_r2c_1d(n, in, out, f); }
  static Plan c2r_1d(int n, Complex* in, double* out, unsigned f) { return fftw_plan_dft_c2r_1d(n, in, out, f); }
  static Plan r2c_2d(int ny, int nx, double* in, Complex* out, unsigned f) {
    return fftw_plan_dft_r2c_2d(ny, nx, in, out, f);
  }
  static Plan c2r_2d(int ny, int nx, Complex* in, double* out, unsigned f) {
    return fftw_plan_dft_c2r_2d(ny, nx, in, out, f);
  }
  static void execute(Plan p) { fftw_execute(p); }
  static void execute_r2c(Plan p, double* in, Complex* out) { fftw_execute_dft_r2c(p, in, out); }
  static void destroy(Plan p) { fftw_destroy_plan(p); }
  static int alignment_of(double* p) { return fftw_alignment_of(p); }
  static char* export_wisdom() { return fftw_export_wisdom_to_string(); }
  static void import_wisdom(const char* w) { fftw_import_wisdom_from_string(w); }
  static void free_string(char* w) { fftw_free(w); }
};

template <>
struct FftwApi<float> {
  using Plan = fftwf_plan;
  using Complex = fftwf_complex;
  static constexpr const char* wisdom_suffix = "-single";
  static void init_threads() { fftwf_init_threads(); }
  static void plan_with_nthreads(int n) { fftwf_plan_with_nthreads(n); }
  static Plan r2c_1d(int n, float* in, Complex* out, unsigned f) { return fftwf_plan_dft_r2c_1d(n, in, out, f); }
  static Plan c2r_1d(int n, Complex* in, float* out, unsigned f) { return fftwf_plan_dft_c2r_1d(n, in, out, f); }
  static Plan r2c_2d(int ny, int nx, float* in, Complex* out, unsigned f) {
    return fftwf_plan_dft_r2c_2d(ny, nx, in, out, f);
  }
  static Plan c2r_2d(int ny, int nx, Complex* in, float* out, unsigned f) {
    return fftwf_plan_dft_c2r_2d(ny, nx, in, out, f);
  }
  static void execute(Plan p) { fftwf_execute(p); }
  static void execute_r2c(Plan p, float* in, Complex* out) { fftwf_execute_dft_r2c(p, in, out); }
  static void destroy(Plan p) { fftwf_destroy_plan(p); }
  static int alignment_of(float* p) { return fftwf_alignment_of(p); }
  static char* export_wisdom() { return fftwf_export_wisdom_to_string(); }
  static void import_wisdom(const char* w) { fftwf_import_wisdom_from_string(w); }
  static void free_string(char* w) { fftwf_free(w); }
};

namespace {

template <class Real>
std::string wisdom_path() {
  const std::string base = fft_wisdom_path();
  return base.empty() ? base : base + FftwApi<Real>::wisdom_suffix;
}

template <class Real>
std::string wisdom_string() {
  char* w = FftwApi<Real>::export_wisdom();
  std::string s = w ? w : "";
  if (w) FftwApi<Real>::free_string(w);
  return s;
}

// Reads the wisdom file into FFTW (once per process and precision); unreadable or stale files
// are ignored.
template <class Real>
void import_wisdom_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    const std::string path = wisdom_path<Real>();
    if (path.empty()) return;
    std::ifstream in(path);
    if (!in) return;
    std::ostringstream text;
    text << in.rdbuf();
    FftwApi<Real>::import_wisdom(text.str().c_str());
  });
}

// Writes FFTW's wisdom back when planning added to it: to a temporary file renamed over the old
// one, so that concurrent processes (MPI ranks, sweeps) never read a half-written file.
template <class Real>
void save_wisdom_if_grown(const std::string& before) {
  const std::string path = wisdom_path<Real>();
  const std::string after = wisdom_string<Real>();
  if (path.empty() || after == before) return;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp);
    out << after;
    if (!out) {
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace

template <class Real>
BasicRealFft2d<Real>::BasicRealFft2d(std::size_t nx, std::size_t ny, int threads, Real* external_real,
                                     FftPlanning planning, FftInput input)
    : nx_(nx), ny_(ny), destroys_input_(input != FftInput::preserve), in_place_(input == FftInput::in_place) {
  using Api = FftwApi<Real>;
  // FFTW keeps its thread support process-wide; initialising it twice is harmless but
  // call_once keeps it cheap.
  static std::once_flag init;
  std::call_once(init, [] { Api::init_threads(); });
  if (threads <= 0) threads = hardware_threads();
  owns_real_ = external_real == nullptr;
  real_ = owns_real_ ? static_cast<Real*>(allocate_big(ny * row_stride() * sizeof(Real))) : external_real;
  spec_ = in_place_ ? reinterpret_cast<std::complex<Real>*>(real_)
                    : static_cast<std::complex<Real>*>(allocate_big(ny * nxh() * sizeof(std::complex<Real>)));

  // Small transforms gain nothing from threads.
  Api::plan_with_nthreads(nx * ny >= (1u << 16) ? threads : 1);
  auto* c = reinterpret_cast<typename Api::Complex*>(spec_);
  const bool measure = planning == FftPlanning::measure;
  const unsigned flags = (measure ? FFTW_MEASURE : FFTW_ESTIMATE) | (destroys_input_ ? FFTW_DESTROY_INPUT : 0u);
  std::string before;
  if (measure) {
    import_wisdom_once<Real>();
    before = wisdom_string<Real>();
  }
  if (ny == 1) {
    fwd_ = Api::r2c_1d(static_cast<int>(nx), real_, c, flags);
    bwd_ = Api::c2r_1d(static_cast<int>(nx), c, real_, flags);
  } else {
    fwd_ = Api::r2c_2d(static_cast<int>(ny), static_cast<int>(nx), real_, c, flags);
    bwd_ = Api::c2r_2d(static_cast<int>(ny), static_cast<int>(nx), c, real_, flags);
  }
  if (measure) save_wisdom_if_grown<Real>(before);
}

template <class Real>
BasicRealFft2d<Real>::~BasicRealFft2d() {
  if (fwd_) FftwApi<Real>::destroy(fwd_);
  if (bwd_) FftwApi<Real>::destroy(bwd_);
  if (owns_real_) free_big(real_, ny_ * row_stride() * sizeof(Real));
  if (!in_place_) free_big(spec_, ny_ * nxh() * sizeof(std::complex<Real>));
}

template <class Real>
void BasicRealFft2d<Real>::forward() {
  FftwApi<Real>::execute(fwd_);
}
template <class Real>
void BasicRealFft2d<Real>::backward() {
  FftwApi<Real>::execute(bwd_);
}

template <class Real>
void BasicRealFft2d<Real>::forward_from(const Real* in) {
  auto* x = const_cast<Real*>(in);  // r2c plans preserve their input unless destroys_input_
  if (x == real_) return forward();
  if (destroys_input_ || FftwApi<Real>::alignment_of(x) != FftwApi<Real>::alignment_of(real_)) {
    std::copy(in, in + ny_ * row_stride(), real_);
    return forward();
  }
  FftwApi<Real>::execute_r2c(fwd_, x, reinterpret_cast<typename FftwApi<Real>::Complex*>(spec_));
}

template class BasicRealFft2d<double>;
template class BasicRealFft2d<float>;

}  // namespace wr
