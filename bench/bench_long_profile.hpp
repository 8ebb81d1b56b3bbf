#pragma once
// `wetroad bench long-profile`: `analyze` of a continuous laser texture record (issue 54 bar 2: a
// 10 km record at 0.5 mm is 20 million samples, with dropouts and spikes).
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace wr::bench {

struct LongProfileOptions {
  std::size_t samples = 20'000'000;
  double dx = 0.5e-3;                // m
  double evaluation_length = 10.0;   // m (ISO 13473-1 per-evaluation-length MPD)
  double dropout_share = 0.01;       // of the samples, in bursts of 1-16 samples
  double spike_rate = 2e-4;          // spikes per sample
  std::uint64_t seed = 1;
  int threads = 0;
  std::string file;                  // where the record goes (kept); empty: a temporary file, removed
  std::string scratch_dir;           // for the temporary file
};

// Writes the synthetic record as an HDF5 /profile (attribute dx, NaN dropouts) in one forked child,
// then reads and analyzes it in another exactly as `wetroad analyze FILE` does (continuous MPD,
// reference plates cut, MPD per evaluation length), so that the peak resident memory reported is
// that of the analysis alone: wall time per phase, peak RSS, and the MPD figures.
nlohmann::json long_profile(const LongProfileOptions& o);

}  // namespace wr::bench
