#pragma once
// Random-phase synthesis of a periodic, isotropic, self-affine surface (thesis sec. 4.1).
//
// Each lattice wave-vector q (multiples of 2 pi / Lx, 2 pi / Ly) with qL <= |q| <= q1_cut gets
// the deterministic amplitude |B_q| = sqrt(C(q) qLx qLy) (eq. 4.2) and a uniform random phase;
// an inverse real FFT (FFTW) sums the waves. The spectrum is Hermitian by construction so the
// surface is real and periodic.
//
// Normalisation: eq. 4.4 makes the *continuous* integral of C equal h0^2; the lattice sum
// differs from the integral (ring quantisation near qL, the discrete cut at q1), so the plateau
// is rescaled to make the lattice sum over the uncut spectrum equal h0^2 exactly. The measured
// h0 of the uncut surface therefore equals the prescribed one to rounding; how far eq. 4.4 alone
// would land is reported in `h0_eq44_on_lattice`.
//
// Determinism: the phase of each half-spectrum wave-vector is a counter-based hash (SplitMix64)
// of (seed, index), so the fill runs in parallel, the parallel power sum is combined in a fixed
// chunk order, and the FFT plan is FFTW_ESTIMATE: the same options give a bit-identical map,
// and changing h0 or the low-pass fraction changes the amplitudes of the same waves only.
//
// Sampling::thesis reproduces the thesis's surfaces (sec. 4.1.1, Table 5.1): its waves run up
// to q1 = 2 pi / dx (eq. 4.1), twice the grid's Nyquist wavenumber, and its sum of sinusoids is
// evaluated at the lattice points, so the waves above Nyquist alias onto lower wavenumbers
// (their heights are exact at the points; between them the triangulated lattice is all there
// is). Implemented as the band-limited synthesis on the grid S = ceil(q1 dx / pi) times finer
// (the same wave lattice, multiples of qL) sampled at every S-th point, mean removed. The
// aliased power makes the lattice steeper than a band-limited surface of the same h0 (forward
// differences: +8.5 % at the thesis's dataset-A spectrum) and lifts the measured PSD's
// decaying part, as the thesis's Figure 4.3 notes.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lib/core/height_map.hpp"
#include "roads/self_affine_psd.hpp"

namespace wr {

// How the waves meet the grid: band-limited (q1 defaults to Nyquist pi/dx, and a q1 above it
// is refused) or as the thesis sampled them (q1 defaults to 2 pi/dx, waves above Nyquist aliased).
enum class Sampling { nyquist, thesis };
const std::vector<std::pair<std::string, Sampling>>& sampling_names();  // for the CLI's transformer
const char* sampling_name(Sampling s);
std::optional<Sampling> sampling_from_name(const std::string& name);  // nullopt: unknown

struct SynthParams {
  std::size_t nx = 300, ny = 300;  // grid points before oversampling
  double dx = 1e-4;                // m, spacing before oversampling (dy = dx)
  double h0 = 3e-4;                // m rms
  double hurst = 0.7;
  double q0_ratio = 5.0;           // q0 / qL
  std::optional<double> q1;        // 1/m; default the (oversampled) grid's Nyquist pi/dx
  double q1_fraction = 1.0;        // low-pass: keep q <= q1_fraction * q1 (dataset C)
  int oversample = 1;              // generate on a grid S times finer (nx*S, dx/S)
  Sampling sampling = Sampling::nyquist;  // thesis: q1 default 2 pi/dx, aliased (not with oversample)
  std::uint64_t seed = 1;          // 0 ... kMaxSeed
  int threads = 0;                 // FFT threads, 0 = hardware
};

// The one range of seeds, checked on input everywhere: a seed is written to HDF5 as an int64
// and to JSON as a number that readers may hold as a double, exact only up to 2^53.
inline constexpr double kMaxRoadH0 = 0.01;  // m: the largest rms height synthesized (validate)
inline constexpr std::uint64_t kMaxSeed = (std::uint64_t{1} << 53) - 1;

struct SynthResult {
  HeightMap map;                   // periodic, mean zero
  SelfAffinePsd psd;               // the prescribed spectrum, with the lattice-normalised k
  double k_eq44 = 0;               // plateau from eq. 4.4 alone, m^4
  double h0_eq44_on_lattice = 0;   // m: rms height the lattice would give with k_eq44
  std::size_t active_waves = 0;    // lattice wave-vectors with non-zero amplitude (full plane)
};

// Throws InputError("--option", ...) for invalid parameters, including a q1 above the grid's
// Nyquist wavenumber under Sampling::nyquist (the message offers --oversample and --sampling
// thesis), --oversample with --sampling thesis, and grids that do not fit memory.
void validate(const SynthParams& p);
SynthResult synthesize(const SynthParams& p);

}  // namespace wr
