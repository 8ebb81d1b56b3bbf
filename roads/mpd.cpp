#include "roads/mpd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lib/core/parallel.hpp"
#include "roads/profile_filters.hpp"
#include "roads/reference_plates.hpp"

namespace wr {

double standard_spacing(double dx) {
  constexpr double kFine = 0.5e-3, kCoarse = 1.0e-3;  // clause 7.4
  if (dx <= kFine * (1 + 1e-9)) return kFine;
  if (dx <= kCoarse * (1 + 1e-9)) return kCoarse;
  return dx;
}

double mean_segment_depth(const double* h, std::size_t n, bool remove_line) {
  // Least-squares line over the segment, in centred sample units.
  const double c = 0.5 * double(n - 1);
  double sxx = 0, sxy = 0, sy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = double(i) - c;
    sxx += x * x;
    sxy += x * h[i];
    sy += h[i];
  }
  const double mean = sy / double(n), slope = remove_line && sxx > 0 ? sxy / sxx : 0.0;
  const std::size_t half = n / 2;
  double p1 = -INFINITY, p2 = -INFINITY;
  for (std::size_t i = 0; i < half; ++i) p1 = std::max(p1, h[i] - mean - slope * (double(i) - c));
  for (std::size_t i = half; i < n; ++i) p2 = std::max(p2, h[i] - mean - slope * (double(i) - c));
  return 0.5 * (p1 + p2);
}

namespace {

// Clause 7.4, or the raw samples as they are (one per bin) where resampling is off or the raw
// spacing is already the standard's.
// The raw heights are moved from, not copied: a continuous record of 10 km at 0.5 mm is 160 MB
// a copy (issue 54).
ResampledProfile standard_samples(std::vector<double>&& h, const std::vector<unsigned char>& dropout, double dx,
                                  const MpdOptions& opt, MpdAccumulator& acc) {
  const double spacing = opt.resample ? standard_spacing(dx) : dx;
  if (spacing > 1.0e-3 * (1 + 1e-9)) acc.coarse_sampling = true;
  if (std::abs(spacing - dx) > 1e-9 * spacing)
    return resample_bin_average(h.data(), dropout.data(), h.size(), dx, spacing);
  ResampledProfile r;
  r.spacing = dx;
  r.h = std::move(h);
  r.raw.assign(r.h.size(), 1);
  r.dropouts.assign(dropout.begin(), dropout.end());
  return r;
}

}  // namespace

void add_profile_segments(std::vector<double> h, std::vector<unsigned char> dropout, double dx,
                          const MpdOptions& opt, MpdAccumulator& acc, std::size_t profile) {
  ++acc.profiles;
  double origin = 0;  // m, where the evaluated profile starts on the record (after a cut plate)
  if (opt.cut_plates) {
    const PlateCut plates = find_reference_plates(h.data(), dropout.data(), h.size(), dx);
    origin = double(plates.start) * dx;
    acc.plate_start += double(plates.start) * dx;
    acc.plate_end += double(plates.end) * dx;
    h.erase(h.end() - std::ptrdiff_t(plates.end), h.end());
    h.erase(h.begin(), h.begin() + std::ptrdiff_t(plates.start));
    dropout.erase(dropout.end() - std::ptrdiff_t(plates.end), dropout.end());
    dropout.erase(dropout.begin(), dropout.begin() + std::ptrdiff_t(plates.start));
  }
  if (!interpolate_invalid(h.data(), dropout.data(), h.size())) return;  // all dropouts: no segment
  ResampledProfile p = standard_samples(std::move(h), dropout, dx, opt, acc);
  const std::size_t n = p.h.size();
  acc.spacing = p.spacing;
  std::vector<unsigned char> spike(n, 0);
  const std::size_t spikes = opt.spike_alpha > 0 ? mark_spikes(p.h.data(), spike.data(), n, p.spacing, opt.spike_alpha) : 0;
  acc.spikes += spikes;
  if (spikes && !interpolate_invalid(p.h.data(), spike.data(), n)) return;
  if (opt.method == MpdMethod::continuous && opt.highpass_wavelength > 0)
    butterworth_zero_phase(p.h.data(), n, p.spacing, opt.highpass_wavelength, PassBand::highpass);
  if (opt.lowpass_wavelength > 0 &&
      !butterworth_zero_phase(p.h.data(), n, p.spacing, opt.lowpass_wavelength, PassBand::lowpass))
    acc.lowpass_skipped = true;

  std::size_t seg = static_cast<std::size_t>(std::llround(opt.baseline / p.spacing));
  if (seg < 2 || seg > n) {  // shorter than the baseline: one segment over the available length
    seg = n - n % 2;
    acc.short_baseline = true;
    if (seg < 2) return;
  }
  const double used = double(seg) * p.spacing;
  acc.shortest_baseline = acc.shortest_baseline == 0 ? used : std::min(acc.shortest_baseline, used);
  // Evaluation lengths: runs of `per_eval` consecutive segments, on profiles at least one
  // evaluation length long (a shorter one has no evaluation length to report).
  std::size_t per_eval = 0;
  if (opt.evaluation_length > 0 && double(n) * p.spacing >= opt.evaluation_length * (1 - 1e-9))
    per_eval = std::max<std::size_t>(1, std::size_t(std::llround(opt.evaluation_length / used)));
  const std::size_t first_eval = acc.evaluations.size();
  std::vector<double> eval_sum;  // MSD summed over each evaluation length's valid segments
  for (std::size_t s0 = 0, j = 0; s0 + seg <= n; s0 += seg, ++j) {
    EvaluationMpd* ev = nullptr;
    if (per_eval) {
      if (j % per_eval == 0) {
        EvaluationMpd e;
        e.profile = profile;
        e.start = origin + double(s0) * p.spacing;
        acc.evaluations.push_back(e);
        eval_sum.push_back(0.0);
      }
      ev = &acc.evaluations.back();
      ++ev->segments;
    }
    ++acc.segments;
    std::size_t raw = 0, dropped = 0, spiked = 0;
    for (std::size_t i = s0; i < s0 + seg; ++i) {
      raw += p.raw[i];
      dropped += p.dropouts[i];
      spiked += spike[i] != 0;
    }
    if (double(dropped) > opt.max_dropout_fraction * double(raw) ||
        double(spiked) > opt.max_spike_fraction * double(seg)) {
      ++acc.invalid_segments;
      continue;
    }
    acc.msd.push_back(mean_segment_depth(p.h.data() + s0, seg, opt.method == MpdMethod::spot));
    if (ev) {
      ++ev->valid_segments;
      eval_sum.back() += acc.msd.back();
    }
  }
  for (std::size_t k = first_eval; k < acc.evaluations.size(); ++k) {
    EvaluationMpd& e = acc.evaluations[k];
    e.length = double(e.segments) * used;
    e.complete = e.segments == per_eval;
    e.valid = e.valid_segments > 0 && 2 * e.valid_segments >= e.segments;  // clause 7.10
    e.mpd = e.valid_segments > 0 ? eval_sum[k - first_eval] / double(e.valid_segments) : NAN;
  }
}

MpdResult summarize(const MpdAccumulator& acc, const MpdOptions& opt) {
  MpdResult r;
  r.profiles = acc.profiles;
  r.segments = acc.segments;
  r.valid_segments = acc.msd.size();
  r.spikes = acc.spikes;
  r.spacing = acc.spacing;
  r.plate_start = acc.plate_start;
  r.plate_end = acc.plate_end;
  r.standard_baseline = !acc.short_baseline;
  r.baseline_used = acc.short_baseline ? acc.shortest_baseline : opt.baseline;
  r.lowpass_applied = opt.lowpass_wavelength > 0 && !acc.lowpass_skipped;
  r.valid = 2 * r.valid_segments >= r.segments && r.valid_segments > 0;  // clause 7.10
  r.evaluation_length = opt.evaluation_length;
  r.evaluations = acc.evaluations;
  double eval_sum = 0;
  for (const EvaluationMpd& e : r.evaluations) {
    if (!e.complete || !e.valid) continue;
    ++r.evaluations_counted;
    eval_sum += e.mpd;
    r.evaluation_min = r.evaluations_counted == 1 ? e.mpd : std::min(r.evaluation_min, e.mpd);
    r.evaluation_max = r.evaluations_counted == 1 ? e.mpd : std::max(r.evaluation_max, e.mpd);
  }
  if (r.evaluations_counted) r.evaluation_mean = eval_sum / double(r.evaluations_counted);
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
  const auto flag = [&](const std::string& what) { r.note += (r.note.empty() ? "" : "; ") + what; };
  if (acc.short_baseline) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "non-standard baseline: profiles shorter than %.0f mm, mean segment depth on %.1f mm",
                  opt.baseline * 1e3, r.baseline_used * 1e3);
    flag(buf);
  }
  if (!r.valid) flag("fewer than half the segments valid: not a valid MPD (ISO 13473-1 clause 7.10)");
  if (acc.coarse_sampling) flag("sampled coarser than the standard's 1 mm");
  if (!opt.resample) flag("raw sampling kept: not resampled as ISO 13473-1 clause 7.4 asks");
  if (acc.plate_start > 0 || acc.plate_end > 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "reference plates cut: %.1f mm at the start, %.1f mm at the end",
                  acc.plate_start * 1e3, acc.plate_end * 1e3);
    flag(buf);
  }
  if (acc.lowpass_skipped) flag("sampling too coarse for the low-pass");
  return r;
}

void merge(MpdAccumulator& acc, const MpdAccumulator& o) {
  acc.msd.insert(acc.msd.end(), o.msd.begin(), o.msd.end());
  acc.segments += o.segments;
  acc.invalid_segments += o.invalid_segments;
  acc.spikes += o.spikes;
  acc.profiles += o.profiles;
  acc.lowpass_skipped = acc.lowpass_skipped || o.lowpass_skipped;
  acc.coarse_sampling = acc.coarse_sampling || o.coarse_sampling;
  acc.plate_start += o.plate_start;
  acc.plate_end += o.plate_end;
  acc.evaluations.insert(acc.evaluations.end(), o.evaluations.begin(), o.evaluations.end());
  if (o.spacing > 0) acc.spacing = o.spacing;
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
  std::vector<MpdAccumulator> rows(chunks), columns(chunks);
  // Evaluation lengths along the rows only: a map's columns are a crossing direction, not a record.
  MpdOptions column_opt = opt;
  column_opt.evaluation_length = 0;
  parallel_chunks(n_profiles, chunks, threads, [&](std::size_t c, std::size_t p0, std::size_t p1) {
    std::vector<double> line;
    std::vector<unsigned char> bad;
    for (std::size_t k = p0; k < p1; ++k) {
      if (k < map.ny) {
        // Moved into the call: one working copy of a row, not two (a long record is 160 MB a copy).
        line.assign(map.h.begin() + k * map.nx, map.h.begin() + (k + 1) * map.nx);
        bad.assign(dropout.begin() + k * map.nx, dropout.begin() + (k + 1) * map.nx);
        add_profile_segments(std::move(line), std::move(bad), map.dx, opt, rows[c], k);
        line.clear();
        bad.clear();
      } else {
        const std::size_t ix = k - map.ny;
        line.resize(map.ny);
        bad.resize(map.ny);
        for (std::size_t iy = 0; iy < map.ny; ++iy) {
          line[iy] = map(ix, iy);
          bad[iy] = dropout[iy * map.nx + ix];
        }
        add_profile_segments(line, bad, map.dy, column_opt, columns[c]);
      }
    }
  });
  MpdAccumulator x, y;
  for (std::size_t c = 0; c < chunks; ++c) {
    merge(x, rows[c]);
    merge(y, columns[c]);
  }
  MpdAccumulator all = x;
  merge(all, y);
  MpdResult r = summarize(all, opt);
  r.mpd_x = summarize(x, opt).mpd;
  if (!map.is_profile()) r.mpd_y = summarize(y, opt).mpd;
  return r;
}

}  // namespace wr
