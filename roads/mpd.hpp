#pragma once
// Mean profile depth after ISO 13473-1:2019 (clauses 7.3-7.10, Annexes D and E), over every row
// and every column of a map, reported along x (rows), along y (columns) and together.
//
// Per profile: reference plates at the record's ends cut (an option, reference_plates.hpp);
// dropouts corrected on the raw samples (linear inside, held at the ends; 7.3);
// resampled by bin averaging to 0.5 mm, or 1.0 mm when the raw spacing is coarser (7.4);
// spikes after Annex E (neighbours differing by 3 x the spacing or more, both flagged) and
// interpolated; a continuous measurement is high-passed at 174.2 mm; all are low-passed at
// 2.4 mm (Annex D: 2nd-order Butterworth, zero phase); then cut into 100 mm segments by
// distance from the profile's start (the tail that does not fill one is dropped). A spot
// measurement has the least-squares line removed per segment (slope suppression). Mean segment
// depth MSD = (peak of first half + peak of second half) / 2 - segment mean. A segment is
// invalid when more than 10 % of its raw samples were dropouts or more than 5 % of its
// resampled samples spikes (7.8). MPD is the mean MSD of the valid segments, with their
// standard deviation and the valid share; it is valid only when at least half the segments are.
//
// A profile shorter than the baseline gives one segment over its whole (even) length, and the
// result is flagged non-standard: that is a mean segment depth on the available length, not an
// ISO MPD.
#include <cmath>
#include <string>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

enum class MpdMethod { spot, continuous };

struct MpdOptions {
  double baseline = 0.100;              // m, ISO segment length
  double lowpass_wavelength = 2.4e-3;   // m (Annex D); <= 0 switches the low-pass off
  double highpass_wavelength = 174.2e-3;  // m (Annex D), continuous measurements only
  MpdMethod method = MpdMethod::spot;   // spot: slope suppression per segment; continuous: high-pass
  bool resample = true;                 // to 0.5 mm (1.0 mm when the raw spacing is coarser)
  double spike_alpha = 3;               // Annex E, eq. E.1; <= 0 switches spike removal off
  double max_dropout_fraction = 0.10;   // of a segment's raw samples
  double max_spike_fraction = 0.05;     // of a segment's resampled samples
  bool cut_plates = false;              // drop reference plates at the record's ends (reference_plates.hpp)
  // m; > 0: the segments are also grouped into consecutive evaluation lengths of this length
  // along each profile (ISO 13473-1:2019 reports a continuous record as one MPD per evaluation
  // length, e.g. 10 m or 20 m), each with its own MPD and validity (7.10). 0: none.
  double evaluation_length = 0;
};

// One evaluation length of a profile: the segments whose start lies in [start, start + length)
// of the profile (after cut reference plates). MPD is the mean MSD of its valid segments; it is
// valid when at least half its segments are (clause 7.10, applied per evaluation length). The
// last one of a profile may be shorter (`complete` false): it is listed, not counted in the
// statistics.
struct EvaluationMpd {
  std::size_t profile = 0;         // index of the profile (row) it belongs to
  double start = 0, length = 0;    // m, from the profile's first sample; length its segments cover
  std::size_t segments = 0, valid_segments = 0;
  double mpd = NAN;                // m
  bool valid = false, complete = false;
};

// The spacing clause 7.4 resamples to from raw spacing dx: 0.5 mm, or 1.0 mm when dx is
// coarser; dx itself when it is coarser still (the result is then flagged).
double standard_spacing(double dx);

// Mean segment depth of one segment (n >= 2 samples), halves' peaks averaged against the mean;
// with `remove_line` the least-squares line is removed first (slope suppression).
double mean_segment_depth(const double* h, std::size_t n, bool remove_line = true);

struct MpdAccumulator {
  std::vector<double> msd;         // valid segment depths, m
  std::size_t segments = 0;        // all segments, valid or not
  std::size_t invalid_segments = 0;
  std::size_t spikes = 0;          // resampled samples flagged
  std::size_t profiles = 0;
  bool lowpass_skipped = false;    // sampling too coarse for the low-pass
  bool coarse_sampling = false;    // raw spacing above 1 mm: not resampled
  bool short_baseline = false;     // some profile shorter than the baseline
  double shortest_baseline = 0;    // m, the shortest segment length used
  double spacing = 0;              // m, the (re)sampled spacing of the last profile
  double plate_start = 0, plate_end = 0;  // m, cut as reference plates (summed over profiles)
  std::vector<EvaluationMpd> evaluations;  // MpdOptions::evaluation_length > 0, in profile order
};

// Processes one profile of n samples (modified: pass a copy, or move a profile no longer
// needed), adding its segments to `acc`. `profile` numbers the evaluation lengths' profile.
void add_profile_segments(std::vector<double> h, std::vector<unsigned char> invalid, double dx,
                          const MpdOptions& opt, MpdAccumulator& acc, std::size_t profile = 0);

struct MpdResult {
  double mpd = 0;       // m
  double mpd_std = 0;   // m, std of the valid segment depths
  std::size_t profiles = 0, segments = 0, valid_segments = 0, spikes = 0;
  bool valid = false;   // at least half the segments valid (7.10)
  double mpd_x = NAN, mpd_y = NAN;  // m, of the rows and of the columns alone (mpd_of_map)
  double plate_start = 0, plate_end = 0;  // m, cut as reference plates (MpdOptions::cut_plates)
  double spacing = 0;   // m, the spacing the profiles were evaluated at
  bool standard_baseline = true;
  double baseline_used = 0;  // m
  bool lowpass_applied = true;
  std::string note;
  // Per evaluation length (MpdOptions::evaluation_length > 0; rows of a map and 1-D profiles
  // only; empty when no profile is as long as one evaluation length), and the count, mean, min
  // and max of the MPD of the complete, valid ones.
  double evaluation_length = 0;  // m, as asked
  std::vector<EvaluationMpd> evaluations;
  std::size_t evaluations_counted = 0;
  double evaluation_mean = NAN, evaluation_min = NAN, evaluation_max = NAN;  // m
};

MpdResult summarize(const MpdAccumulator& acc, const MpdOptions& opt);

// Appends `other` to `acc` (segment depths in order).
void merge(MpdAccumulator& acc, const MpdAccumulator& other);

// All rows (and, for maps, all columns) of `map`; `dropout` marks samples with no valid data.
// The result is of all profiles together, with mpd_x (rows) and mpd_y (columns; NaN for a 1-D
// profile) as a CTMeter reports them. threads <= 0: all hardware threads; the result does not
// depend on the thread count.
MpdResult mpd_of_map(const HeightMap& map, const std::vector<unsigned char>& dropout, const MpdOptions& opt = {},
                     int threads = 0);

// ETD = 0.2 mm + 0.8 MPD (ISO 13473-1 estimate of the sand-patch texture depth), metres.
inline double estimated_texture_depth(double mpd) { return 0.2e-3 + 0.8 * mpd; }

}  // namespace wr
