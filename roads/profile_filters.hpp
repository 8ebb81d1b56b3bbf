#pragma once
// Profile pre-processing of ISO 13473-1:2019 (texture profiles for MPD): dropout correction
// (clause 7.3), resampling (7.4), spike removal (Annex E) and the zero-phase Butterworth filters
// (Annex D). All functions work on n samples spaced dx metres apart; `invalid` marks samples
// that were dropouts or spikes.
#include <cstddef>
#include <vector>

namespace wr {

// Replaces samples with invalid[i] != 0 by linear interpolation between the nearest valid
// samples, the first and last valid values held beyond them (clause 7.3). Returns false when
// no sample is valid.
bool interpolate_invalid(double* h, const unsigned char* invalid, std::size_t n);

// A profile resampled to `spacing` (clause 7.4): output sample k (k = 1, 2, ...) at k x spacing
// from the first raw sample is the mean of the raw samples at distances in ((k - 1) spacing,
// k spacing], the first bin also taking the sample at 0. Every bin that holds a raw sample is
// kept, the last one possibly partly covered (as the reference implementations have it). `raw` counts
// the raw samples of each bin and `dropouts` those of them that were dropouts before
// correction (the segment validity rule counts raw dropouts). Raw samples must be corrected
// already (interpolate_invalid). Requires spacing >= dx > 0.
struct ResampledProfile {
  double spacing = 0;  // m
  std::vector<double> h;
  std::vector<unsigned> raw, dropouts;
};
ResampledProfile resample_bin_average(const double* h, const unsigned char* dropout, std::size_t n, double dx,
                                      double spacing);

// Marks spikes in `invalid` after Annex E: wherever two neighbouring samples differ by at least
// alpha x dx (eq. E.1; the standard's alpha is 3, i.e. a slope of 3), both are flagged. Returns
// how many samples were newly flagged; they are then interpolated like dropouts. The threshold
// is taken inclusive up to rounding (1e-9 relative), so that decimal test profiles do not flip.
std::size_t mark_spikes(const double* h, unsigned char* invalid, std::size_t n, double dx, double alpha);

enum class PassBand { lowpass, highpass };

// Second-order Butterworth (Annex D: bilinear transform pre-warped to the cut-off, gain
// 1 / sqrt(2), -3 dB, at cutoff_wavelength for one pass) run forward then backward, so the
// phase is zero and the gain is that of one pass squared: 1 / (1 + r^4) for the low-pass and
// r^4 / (1 + r^4) for the high-pass, r = tan(pi dx / lambda) / tan(pi dx / cutoff), i.e. -6 dB
// at the cut-off. Ends are padded by odd reflection over 9 samples and the filter starts in the
// steady state of the first padded value, as the reference implementations do (SciPy's and
// MATLAB's filtfilt): a constant passes the low-pass unchanged. Returns false (h unchanged) when
// the cut-off lies above 0.9 of the Nyquist frequency: the sampling is too coarse to filter.
bool butterworth_zero_phase(double* h, std::size_t n, double dx, double cutoff_wavelength, PassBand band);

// The gain of one forward pass at `wavelength` (for tests and reports).
double butterworth_gain(double dx, double cutoff_wavelength, double wavelength, PassBand band);

}  // namespace wr
