#include "roads/synthesize.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

#include "lib/core/errors.hpp"
#include "lib/core/fft.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/core/parallel.hpp"

namespace wr {
namespace {

std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// Signed lattice index of FFT bin i on an n-point axis.
long signed_index(std::size_t i, std::size_t n) {
  return i <= n / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(n);
}

// SplitMix64 finaliser: a counter-based generator, so the phase of each wave-vector depends only
// on (seed, index) and the fill can run in parallel in any order.
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double uniform_phase(std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t bits = mix64(mix64(seed) + 0x9e3779b97f4a7c15ULL * (index + 1));
  return 2 * std::numbers::pi * static_cast<double>(bits >> 11) * 0x1.0p-53;  // 53 bits -> [0, 2 pi)
}

struct Grid {
  std::size_t nx, ny;
  double dx, dy, qLx, qLy, qL;
};

Grid make_grid(const SynthParams& p) {
  Grid g;
  g.nx = p.nx * p.oversample;
  g.ny = p.ny * p.oversample;
  g.dx = g.dy = p.dx / p.oversample;
  g.qLx = 2 * std::numbers::pi / (g.nx * g.dx);
  g.qLy = 2 * std::numbers::pi / (g.ny * g.dy);
  g.qL = std::min(g.qLx, g.qLy);
  return g;
}

double nyquist(const Grid& g) { return std::numbers::pi / std::max(g.dx, g.dy); }

// Thesis sampling: q1 (default 2 pi/dx, eq. 4.1) and the factor of the finer grid whose
// Nyquist wavenumber reaches it.
double thesis_q1(const SynthParams& p) { return p.q1 ? *p.q1 : 2 * std::numbers::pi / p.dx; }

// The factor as a double: validate() bounds it (<= 64) before anything casts it to int.
double thesis_factor_exact(const SynthParams& p) {
  return std::max(1.0, std::ceil(thesis_q1(p) / (std::numbers::pi / p.dx) - 1e-9));
}

int thesis_factor(const SynthParams& p) { return static_cast<int>(thesis_factor_exact(p)); }

SynthParams band_limited_equivalent(const SynthParams& p) {
  SynthParams fine = p;
  fine.sampling = Sampling::nyquist;
  fine.q1 = thesis_q1(p);
  fine.oversample = thesis_factor(p);
  return fine;
}

}  // namespace

const std::vector<std::pair<std::string, Sampling>>& sampling_names() {
  static const std::vector<std::pair<std::string, Sampling>> names{{"nyquist", Sampling::nyquist},
                                                                   {"thesis", Sampling::thesis}};
  return names;
}

const char* sampling_name(Sampling s) {
  for (const auto& [name, value] : sampling_names())
    if (value == s) return name.c_str();
  return "?";
}

std::optional<Sampling> sampling_from_name(const std::string& name) {
  for (const auto& [n, value] : sampling_names())
    if (n == name) return value;
  return std::nullopt;
}

void validate(const SynthParams& p) {
  if (p.sampling == Sampling::thesis) {
    if (p.oversample != 1)
      throw InputError("--oversample", "not with --sampling thesis, which samples the waves above Nyquist on the "
                                       "grid itself; use one or the other");
    if (!(p.dx > 0) || !std::isfinite(p.dx)) throw InputError("--dx", "must be a positive length in m");
    if (p.q1 && !(*p.q1 > 0 && std::isfinite(*p.q1))) throw InputError("--q1", "must be a positive wavenumber in 1/m");
    if (!(thesis_factor_exact(p) <= 64))
      throw InputError("--q1", "more than 64 times the grid's Nyquist wavenumber under --sampling thesis");
    validate(band_limited_equivalent(p));
    return;
  }
  if (p.seed > kMaxSeed) throw InputError("--seed", "must be a whole number in 0 ... " + std::to_string(kMaxSeed));
  if (p.nx < 2 || p.ny < 2) throw InputError("--size", "the grid needs at least 2x2 points");
  if (!(p.dx > 0) || !std::isfinite(p.dx)) throw InputError("--dx", "must be a positive length in m");
  if (!(p.h0 > 0) || !std::isfinite(p.h0)) throw InputError("--h0", "must be a positive rms height in m");
  // Road textures have rms heights of tenths of a millimetre to a few millimetres; beyond 1 cm
  // no model here describes the result (slopes of hundreds, mu of millions), so none is made.
  if (p.h0 > kMaxRoadH0)
    throw InputError("--h0", "an rms height of " + fmt(p.h0) + " m is no road texture (at most " + fmt(kMaxRoadH0) +
                                 " m; a unit given wrong?)");
  if (!(p.hurst > 0 && p.hurst < 1)) throw InputError("--hurst", "must lie in (0, 1)");
  if (!(p.q1_fraction > 0 && p.q1_fraction <= 1)) throw InputError("--q1-fraction", "must lie in (0, 1]");
  if (p.oversample < 1 || p.oversample > 64) throw InputError("--oversample", "must be an integer in 1..64");
  const Grid g = make_grid(p);
  if (!(p.q0_ratio >= 1)) throw InputError("--q0-ratio", "q0/qL must be >= 1");
  checked_cells(g.nx, g.ny, "--size");
  // map + FFT real buffer + half spectrum (complex, ~ one more map)
  require_memory(g.nx * g.ny, sizeof(double), 3.2, "--size",
                 "a " + std::to_string(g.nx) + "x" + std::to_string(g.ny) + " surface");
  const double qn = nyquist(g);
  const double q0 = p.q0_ratio * g.qL;
  if (p.q1) {
    const double q1 = *p.q1;
    if (!(q1 > 0) || !std::isfinite(q1)) throw InputError("--q1", "must be a positive wavenumber in 1/m");
    if (q1 > qn * (1 + 1e-9)) {
      const int s = static_cast<int>(std::ceil(q1 / (std::numbers::pi / p.dx) - 1e-9));
      throw InputError("--q1", "q1 = " + fmt(q1) + " 1/m is above the grid's Nyquist wavenumber pi/dx = " +
                                   fmt(qn) + " 1/m and cannot be represented on this grid without aliasing;"
                                   " add --oversample " + std::to_string(s) + " (generates " +
                                   std::to_string(p.nx * s) + "x" + std::to_string(p.ny * s) +
                                   " points at dx = " + fmt(p.dx / s) + " m), lower --q1, or alias on"
                                   " purpose with --sampling thesis");
    }
    if (q1 <= q0) throw InputError("--q1", "q1 must exceed the roll-off q0 = " + fmt(q0) + " 1/m");
  } else if (qn <= q0) {
    throw InputError("--q0-ratio", "the roll-off q0 = " + fmt(q0) + " 1/m is at or above Nyquist " + fmt(qn));
  }
  // The low-pass keeps q <= f q1: below the lattice's smallest wavenumber qL it keeps no wave at
  // all, and the "surface" would be a flat map of zeros with h0 = 0.
  const double kept = p.q1_fraction * p.q1.value_or(qn);
  if (kept < g.qL)
    throw InputError("--q1-fraction", "keeps q <= " + fmt(kept) + " 1/m, below the lattice's smallest wavenumber qL = " +
                                          fmt(g.qL) + " 1/m: no wave would be left");
}

namespace {
SynthResult synthesize_unchecked(const SynthParams& p);
}  // namespace

SynthResult synthesize(const SynthParams& p) {
  SynthResult r = synthesize_unchecked(p);
  // Lengths near the ends of double's range pass every option check and still overflow in the
  // spectrum (qL = 2 pi / L, k ~ h0^2 / qL^2): a surface with NaN or Inf is no surface.
  bool finite = std::isfinite(r.psd.k) && std::isfinite(r.k_eq44) && std::isfinite(r.h0_eq44_on_lattice);
  for (double v : r.map.h) finite = finite && std::isfinite(v);
  if (!finite)
    throw NumericalError("synth", "the surface came out non-finite (NaN or Inf): h0 " + fmt(p.h0) + " m and dx " +
                                      fmt(p.dx) + " m are beyond double precision's range for this spectrum");
  return r;
}

namespace {
SynthResult synthesize_unchecked(const SynthParams& p) {
  validate(p);
  if (p.sampling == Sampling::thesis) {
    const SynthParams fine_params = band_limited_equivalent(p);
    SynthResult r = synthesize_unchecked(fine_params);
    const std::size_t s = static_cast<std::size_t>(fine_params.oversample);
    HeightMap coarse(p.nx, p.ny, p.dx, p.dx);
    coarse.periodic = true;
    double sum = 0;
    for (std::size_t iy = 0; iy < p.ny; ++iy)
      for (std::size_t ix = 0; ix < p.nx; ++ix) sum += coarse(ix, iy) = r.map(ix * s, iy * s);
    // Waves on the lattice of multiples of (nx, ny) qL alias onto the mean plane.
    const double mean = sum / static_cast<double>(p.nx * p.ny);
    for (double& v : coarse.h) v -= mean;
    r.map = std::move(coarse);
    return r;
  }
  const Grid g = make_grid(p);
  const double q1 = p.q1 ? *p.q1 : nyquist(g);
  const double q0 = p.q0_ratio * g.qL;

  SynthResult r;
  SelfAffinePsd full = SelfAffinePsd::from_eq44(p.h0, p.hurst, g.qL, q0, q1, 1.0);
  r.k_eq44 = full.k;
  SelfAffinePsd cut = full;
  cut.q1_cut = q1 * p.q1_fraction;

  // Amplitudes with the eq. 4.4 plateau first; the lattice power of the uncut spectrum is
  // summed on the way (interior half-plane columns stand for q and -q) and fixes the rescale.
  r.map = HeightMap(g.nx, g.ny, g.dx, g.dy);
  r.map.periodic = true;
  RealFft2d fft(g.nx, g.ny, p.threads, r.map.h.data());  // c2r writes straight into the map
  std::complex<double>* spec = fft.spectrum();
  const std::size_t nxh = fft.nxh();
  const double cell = g.qLx * g.qLy;
  const std::size_t chunks = default_chunks(g.ny);
  std::vector<double> power(chunks, 0.0);
  std::vector<std::size_t> waves(chunks, 0);
  parallel_chunks(g.ny, chunks, p.threads, [&](std::size_t chunk, std::size_t y0, std::size_t y1) {
    double pw = 0;
    std::size_t active = 0;
    for (std::size_t iy = y0; iy < y1; ++iy) {
      const double qy = signed_index(iy, g.ny) * g.qLy;
      for (std::size_t ix = 0; ix < nxh; ++ix) {
        const double qx = signed_index(ix, g.nx) * g.qLx;
        const double q = std::sqrt(qx * qx + qy * qy);
        const double c_full = full(q);
        const double weight = (ix == 0 || (g.nx % 2 == 0 && ix == g.nx / 2)) ? 1.0 : 2.0;
        pw += weight * c_full * cell;
        const double c = q <= cut.q1_cut * (1 + 1e-12) ? c_full : 0.0;
        active += c > 0 ? static_cast<std::size_t>(weight) : 0;
        spec[iy * nxh + ix] = c > 0 ? std::polar(std::sqrt(c * cell), uniform_phase(p.seed, iy * nxh + ix)) : 0.0;
      }
    }
    power[chunk] = pw;
    waves[chunk] = active;
  });
  double power_eq44 = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    power_eq44 += power[c];
    r.active_waves += waves[c];  // non-zero coefficients of the full plane
  }
  r.h0_eq44_on_lattice = std::sqrt(power_eq44);
  const double rescale = p.h0 / r.h0_eq44_on_lattice;
  parallel_chunks(g.ny, chunks, p.threads, [&](std::size_t, std::size_t y0, std::size_t y1) {
    for (std::size_t i = y0 * nxh; i < y1 * nxh; ++i) spec[i] *= rescale;
  });
  r.psd = cut;
  r.psd.k = full.k * rescale * rescale;

  // Columns ix = 0 and ix = nx/2 (even nx) hold both q and -q: make them conjugate pairs, and
  // the self-conjugate points real (sign from the phase), so that c2r sees an exact Hermitian
  // spectrum and the lattice power stays sum |B_q|^2.
  const std::size_t edge_cols[2] = {0, g.nx % 2 == 0 ? g.nx / 2 : 0};
  for (int c = 0; c < (g.nx % 2 == 0 ? 2 : 1); ++c) {
    const std::size_t ix = edge_cols[c];
    for (std::size_t iy = 0; iy < g.ny; ++iy) {
      const std::size_t jy = (g.ny - iy) % g.ny;
      auto& a = spec[iy * nxh + ix];
      if (jy == iy)
        a = std::complex<double>(std::cos(std::arg(a)) >= 0 ? std::abs(a) : -std::abs(a), 0.0);
      else if (iy < jy)
        spec[jy * nxh + ix] = std::conj(a);
    }
  }
  spec[0] = 0.0;  // mean plane at zero

  fft.backward();
  return r;
}
}  // namespace

}  // namespace wr
