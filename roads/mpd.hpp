#pragma once
// Mean profile depth after ISO 13473-1:2019, over every row and column of a map.
//
// Per profile: dropouts interpolated linearly, spikes detected and interpolated
// (profile_filters.hpp), zero-phase low-pass at 2.5 mm; then consecutive segments of the
// 100 mm baseline (the tail that does not fill a segment is dropped). In each segment the
// least-squares line is removed, the segment is split in two halves, and the mean segment
// depth is MSD = (peak of first half + peak of second half) / 2 - mean level (zero after the
// line removal). A segment is invalid when more than 10% of its samples were dropouts or
// spikes. MPD is the mean MSD of all valid segments; its std is the spread of those MSDs.
//
// A profile shorter than the baseline gives one segment over its whole (even) length, and the
// result is flagged non-standard: that is a mean segment depth on the available length, not an
// ISO MPD.
#include <string>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

struct MpdOptions {
  double baseline = 0.100;            // m, ISO segment length
  double lowpass_wavelength = 2.5e-3; // m; <= 0 switches the low-pass off
  double spike_threshold = 0;         // m; <= 0: automatic (see mark_spikes)
  double max_invalid_fraction = 0.10; // segment validity rule
};

// Mean segment depth of one segment (n >= 2 samples): line removed, halves' peaks averaged.
double mean_segment_depth(const double* h, std::size_t n);

struct MpdAccumulator {
  std::vector<double> msd;         // valid segment depths, m
  std::size_t segments = 0;        // all segments, valid or not
  std::size_t invalid_segments = 0;
  std::size_t spikes = 0;
  std::size_t profiles = 0;
  bool lowpass_skipped = false;    // sampling too coarse for the 2.5 mm filter
  bool short_baseline = false;     // some profile shorter than the baseline
  double shortest_baseline = 0;    // m, the shortest segment length used
};

// Processes one profile of n samples (a copy is modified), adding its segments to `acc`.
void add_profile_segments(std::vector<double> h, std::vector<unsigned char> invalid, double dx,
                          const MpdOptions& opt, MpdAccumulator& acc);

struct MpdResult {
  double mpd = 0;       // m
  double mpd_std = 0;   // m, std of the valid segment depths
  std::size_t profiles = 0, segments = 0, valid_segments = 0, spikes = 0;
  bool standard_baseline = true;
  double baseline_used = 0;  // m
  bool lowpass_applied = true;
  std::string note;
};

MpdResult summarize(const MpdAccumulator& acc, const MpdOptions& opt);

// Appends `other` to `acc` (segment depths in order).
void merge(MpdAccumulator& acc, const MpdAccumulator& other);

// All rows (and, for maps, all columns) of `map`; `dropout` marks samples with no valid data.
// threads <= 0: all hardware threads; the result does not depend on the thread count.
MpdResult mpd_of_map(const HeightMap& map, const std::vector<unsigned char>& dropout,
                     const MpdOptions& opt = {}, int threads = 0);

// ETD = 0.2 mm + 0.8 MPD (ISO 13473-1 estimate of the sand-patch texture depth), metres.
inline double estimated_texture_depth(double mpd) { return 0.2e-3 + 0.8 * mpd; }

}  // namespace wr
