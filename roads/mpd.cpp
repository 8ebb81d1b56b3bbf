#include "roads/mpd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lib/core/parallel.hpp"
#include "roads/profile_filters.hpp"

namespace wr {

double mean_segment_depth(const double* h, std::size_t n) {
  // Least-squares line over the segment, in centred sample units.
  const double c = 0.5 * double(n - 1);
  double sxx = 0, sxy = 0, sy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = double(i) - c;
    sxx += x * x;
    sxy += x * h[i];
    sy += h[i];
  }
  const double mean = sy / double(n), slope = sxx > 0 ? sxy / sxx : 0.0;
  const std::size_t half = n / 2;
  double p1 = -INFINITY, p2 = -INFINITY;
  for (std::size_t i = 0; i < half; ++i) p1 = std::max(p1, h[i] - mean - slope * (double(i) - c));
  for (std::size_t i = half; i < n; ++i) p2 = std::max(p2, h[i] - mean - slope * (double(i) - c));
  return 0.5 * (p1 + p2);
}

void add_profile_segments(std::vector<double> h, std::vector<unsigned char> invalid, double dx,
                          const MpdOptions& opt, MpdAccumulator& acc) {
  const std::size_t n = h.size();
  ++acc.profiles;
  if (!interpolate_invalid(h.data(), invalid.data(), n)) return;  // all dropouts: no segment
  const std::size_t spikes = mark_spikes(h.data(), invalid.data(), n, opt.spike_threshold);
  acc.spikes += spikes;
  if (spikes) interpolate_invalid(h.data(), invalid.data(), n);
  if (opt.lowpass_wavelength > 0 && !lowpass_zero_phase(h.data(), n, dx, opt.lowpass_wavelength))
    acc.lowpass_skipped = true;

  std::size_t seg = static_cast<std::size_t>(std::llround(opt.baseline / dx));
  if (seg < 2 || seg > n) {  // shorter than the baseline: one segment over the available length
    seg = n - n % 2;
    acc.short_baseline = true;
  }
  const double used = double(seg) * dx;
  acc.shortest_baseline = acc.shortest_baseline == 0 ? used : std::min(acc.shortest_baseline, used);
  for (std::size_t s0 = 0; s0 + seg <= n; s0 += seg) {
    ++acc.segments;
    std::size_t bad = 0;
    for (std::size_t i = s0; i < s0 + seg; ++i) bad += invalid[i] != 0;
    if (double(bad) > opt.max_invalid_fraction * double(seg)) {
      ++acc.invalid_segments;
      continue;
    }
    acc.msd.push_back(mean_segment_depth(h.data() + s0, seg));
  }
}

MpdResult summarize(const MpdAccumulator& acc, const MpdOptions& opt) {
  MpdResult r;
  r.profiles = acc.profiles;
  r.segments = acc.segments;
  r.valid_segments = acc.msd.size();
  r.spikes = acc.spikes;
  r.standard_baseline = !acc.short_baseline;
  r.baseline_used = acc.short_baseline ? acc.shortest_baseline : opt.baseline;
  r.lowpass_applied = opt.lowpass_wavelength > 0 && !acc.lowpass_skipped;
  if (acc.msd.empty()) {
    r.mpd = r.mpd_std = NAN;
    r.note = "no valid segment";
    return r;
  }
  double s = 0;
  for (double v : acc.msd) s += v;
  r.mpd = s / double(acc.msd.size());
  double s2 = 0;
  for (double v : acc.msd) s2 += (v - r.mpd) * (v - r.mpd);
  r.mpd_std = acc.msd.size() > 1 ? std::sqrt(s2 / double(acc.msd.size() - 1)) : 0.0;
  char buf[200];
  if (acc.short_baseline) {
    std::snprintf(buf, sizeof buf,
                  "non-standard baseline: profiles shorter than %.0f mm, mean segment depth on %.1f mm",
                  opt.baseline * 1e3, r.baseline_used * 1e3);
    r.note = buf;
  }
  if (acc.lowpass_skipped) r.note += std::string(r.note.empty() ? "" : "; ") + "sampling too coarse for the 2.5 mm low-pass";
  return r;
}

void merge(MpdAccumulator& acc, const MpdAccumulator& o) {
  acc.msd.insert(acc.msd.end(), o.msd.begin(), o.msd.end());
  acc.segments += o.segments;
  acc.invalid_segments += o.invalid_segments;
  acc.spikes += o.spikes;
  acc.profiles += o.profiles;
  acc.lowpass_skipped = acc.lowpass_skipped || o.lowpass_skipped;
  acc.short_baseline = acc.short_baseline || o.short_baseline;
  if (o.shortest_baseline > 0)
    acc.shortest_baseline =
        acc.shortest_baseline == 0 ? o.shortest_baseline : std::min(acc.shortest_baseline, o.shortest_baseline);
}

MpdResult mpd_of_map(const HeightMap& map, const std::vector<unsigned char>& dropout, const MpdOptions& opt,
                     int threads) {
  // Profiles 0..ny-1 are the rows; ny..ny+nx-1 the columns (maps only).
  const std::size_t n_profiles = map.ny + (map.is_profile() ? 0 : map.nx);
  const std::size_t chunks = default_chunks(n_profiles);
  std::vector<MpdAccumulator> part(chunks);
  parallel_chunks(n_profiles, chunks, threads, [&](std::size_t c, std::size_t p0, std::size_t p1) {
    std::vector<double> line;
    std::vector<unsigned char> bad;
    for (std::size_t k = p0; k < p1; ++k) {
      if (k < map.ny) {
        line.assign(map.h.begin() + k * map.nx, map.h.begin() + (k + 1) * map.nx);
        bad.assign(dropout.begin() + k * map.nx, dropout.begin() + (k + 1) * map.nx);
        add_profile_segments(line, bad, map.dx, opt, part[c]);
      } else {
        const std::size_t ix = k - map.ny;
        line.resize(map.ny);
        bad.resize(map.ny);
        for (std::size_t iy = 0; iy < map.ny; ++iy) {
          line[iy] = map(ix, iy);
          bad[iy] = dropout[iy * map.nx + ix];
        }
        add_profile_segments(line, bad, map.dy, opt, part[c]);
      }
    }
  });
  MpdAccumulator acc;
  for (const auto& p : part) merge(acc, p);
  return summarize(acc, opt);
}

}  // namespace wr
