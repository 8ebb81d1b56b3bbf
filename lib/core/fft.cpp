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

namespace {

std::string wisdom_string() {
  char* w = fftw_export_wisdom_to_string();
  std::string s = w ? w : "";
  fftw_free(w);
  return s;
}

// Reads the wisdom file into FFTW (once per process); unreadable or stale files are ignored.
void import_wisdom_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    const std::string path = fft_wisdom_path();
    if (path.empty()) return;
    std::ifstream in(path);
    if (!in) return;
    std::ostringstream text;
    text << in.rdbuf();
    fftw_import_wisdom_from_string(text.str().c_str());
  });
}

// Writes FFTW's wisdom back when planning added to it: to a temporary file renamed over the old
// one, so that concurrent processes (MPI ranks, sweeps) never read a half-written file.
void save_wisdom_if_grown(const std::string& before) {
  const std::string path = fft_wisdom_path();
  const std::string after = wisdom_string();
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

RealFft2d::RealFft2d(std::size_t nx, std::size_t ny, int threads, double* external_real, FftPlanning planning)
    : nx_(nx), ny_(ny) {
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
  const bool measure = planning == FftPlanning::measure;
  const unsigned flags = measure ? FFTW_MEASURE : FFTW_ESTIMATE;
  std::string before;
  if (measure) {
    import_wisdom_once();
    before = wisdom_string();
  }
  if (ny == 1) {
    fwd_ = fftw_plan_dft_r2c_1d(static_cast<int>(nx), real_, c, flags);
    bwd_ = fftw_plan_dft_c2r_1d(static_cast<int>(nx), c, real_, flags);
  } else {
    fwd_ = fftw_plan_dft_r2c_2d(static_cast<int>(ny), static_cast<int>(nx), real_, c, flags);
    bwd_ = fftw_plan_dft_c2r_2d(static_cast<int>(ny), static_cast<int>(nx), c, real_, flags);
  }
  if (measure) save_wisdom_if_grown(before);
}

RealFft2d::~RealFft2d() {
  if (fwd_) fftw_destroy_plan(fwd_);
  if (bwd_) fftw_destroy_plan(bwd_);
  if (owns_real_) free_big(real_, nx_ * ny_ * sizeof(double));
  free_big(spec_, ny_ * nxh() * sizeof(std::complex<double>));
}

void RealFft2d::forward() { fftw_execute(fwd_); }
void RealFft2d::backward() { fftw_execute(bwd_); }

void RealFft2d::forward_from(const double* in) {
  auto* x = const_cast<double*>(in);  // r2c plans preserve their input
  if (x == real_) return forward();
  if (fftw_alignment_of(x) != fftw_alignment_of(real_)) {
    std::copy(in, in + nx_ * ny_, real_);
    return forward();
  }
  fftw_execute_dft_r2c(fwd_, x, reinterpret_cast<fftw_complex*>(spec_));
}

}  // namespace wr
