#pragma once
// Profile pre-processing of ISO 13473-1:2019 (texture profiles for MPD): dropout interpolation,
// spike removal and a zero-phase low-pass filter. All functions work in place on n samples
// spaced dx metres apart; `invalid` marks samples that were dropouts or spikes.
#include <cstddef>
#include <vector>

namespace wr {

// Replaces samples with invalid[i] != 0 by linear interpolation between the nearest valid
// samples (constant beyond the ends). Returns false when no sample is valid.
bool interpolate_invalid(double* h, const unsigned char* invalid, std::size_t n);

// Marks spikes in `invalid` and returns how many were found. A spike is a sample that jumps by
// more than `threshold` (m) from both neighbours in the same direction; threshold <= 0 picks
// 6 times the rms sample-to-sample difference of the profile, which a Gaussian texture
// practically never exceeds but a single-sample sensor spike always does. Spikes are then
// interpolated like dropouts.
std::size_t mark_spikes(const double* h, unsigned char* invalid, std::size_t n, double threshold);

// Second-order Butterworth low-pass (bilinear transform, -3 dB at cutoff_wavelength) run
// forward then backward, so the phase is zero and the amplitude response is
// 1 / (1 + (cutoff_wavelength / lambda)^4) for a wave of wavelength lambda (up to the bilinear
// warping). Ends are padded by odd reflection and the filter starts in steady state, so a
// constant or a straight line passes unchanged. Returns false (and leaves h unchanged) when
// the cut-off lies above 0.9 of the Nyquist frequency: the sampling is too coarse to filter.
bool lowpass_zero_phase(double* h, std::size_t n, double dx, double cutoff_wavelength);

}  // namespace wr
