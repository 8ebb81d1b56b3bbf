// A long continuous texture record, synthesized, written and analyzed (bench_long_profile.hpp).
#include "bench/bench_long_profile.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>

#include "bench/bench_common.hpp"
#include "lib/core/provenance.hpp"
#include "roads/analyze.hpp"
#include "roads/surface_file.hpp"
#include "roads/surface_import.hpp"

namespace wr::bench {
namespace {

// A road-like record: macrotexture as a first-order autoregressive process (correlation length
// 3 mm, sd 0.6 mm: MPD of the order of 1 mm, as on a surface dressing), megatexture and
// unevenness as a slower one (0.5 m, 3 mm), a 20 m long gentle grade wave (the laser's height
// over the road as the vehicle pitches: the continuous method's high-pass removes it); dropouts
// in bursts (NaN: the instrument's invalid readings) and spikes of 5-30 mm (Annex E's target).
HeightMap synthetic_record(const LongProfileOptions& o, std::size_t& dropouts, std::size_t& spikes) {
  HeightMap m(o.samples, 1, o.dx, o.dx, HeightMap::Kind::profile);
  m.periodic = false;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  const double a1 = std::exp(-o.dx / 3e-3), s1 = 0.6e-3 * std::sqrt(1 - a1 * a1);
  const double a2 = std::exp(-o.dx / 0.5), s2 = 3e-3 * std::sqrt(1 - a2 * a2);
  double x1 = 0, x2 = 0;
  const double burst_start = o.dropout_share / 8.5;  // mean burst length 8.5 samples
  std::size_t burst_left = 0;
  dropouts = spikes = 0;
  for (std::size_t i = 0; i < o.samples; ++i) {
    x1 = a1 * x1 + s1 * g(rng);
    x2 = a2 * x2 + s2 * g(rng);
    double h = x1 + x2 + 0.02 * std::sin(2 * std::numbers::pi * double(i) * o.dx / 20.0);
    if (burst_left == 0 && u(rng) < burst_start) burst_left = 1 + std::size_t(u(rng) * 16);
    if (u(rng) < o.spike_rate) {
      h += (u(rng) < 0.5 ? -1 : 1) * (5e-3 + 25e-3 * u(rng));
      ++spikes;
    }
    if (burst_left > 0) {
      h = std::numeric_limits<double>::quiet_NaN();
      --burst_left;
      ++dropouts;
    }
    m.h[i] = h;
  }
  return m;
}

}  // namespace

nlohmann::json long_profile(const LongProfileOptions& o) {
  const bool keep = !o.file.empty();
  const std::string path =
      keep ? o.file : (std::filesystem::path(o.scratch_dir) / ("wetroad-long-profile-" + std::to_string(getpid()) + ".h5")).string();
  nlohmann::json made = in_child([&] {
    const double t0 = now();
    std::size_t dropouts = 0, spikes = 0;
    const HeightMap m = synthetic_record(o, dropouts, spikes);
    const double t1 = now();
    write_surface_file(path, m, std::nullopt, {{"command", "bench long-profile"}, {"seed", o.seed}});
    return nlohmann::json{{"synth_s", t1 - t0}, {"write_s", now() - t1}, {"dropouts", dropouts}, {"spikes_added", spikes}};
  });
  if (made.contains("error")) return made;
  nlohmann::json r = in_child([&] {
    const double t0 = now();
    const LoadedSurface s = load_surface(path);
    const double t1 = now();
    AnalysisOptions opt;  // as `wetroad analyze` sets them for a 1-D profile (app/cmd_analyze.cpp)
    opt.threads = o.threads;
    opt.mpd.method = MpdMethod::continuous;
    opt.mpd.cut_plates = true;
    opt.mpd.evaluation_length = o.evaluation_length;
    opt.expected_mpd = true;  // no synthesis record: nothing to expect, as in the CLI
    const AnalysisReport a = analyze_surface(s, opt);
    const double t2 = now();
    const MpdResult& mpd = a.mpd;
    return nlohmann::json{{"read_s", t1 - t0},
                          {"analyze_s", t2 - t1},
                          {"total_s", t2 - t0},
                          {"phases_s", a.timer.to_json()},
                          {"peak_rss_bytes", double(peak_rss_bytes())},
                          {"profile_bytes", double(s.map.h.size() * sizeof(double))},
                          {"dropouts_read", s.dropouts},
                          {"mpd", mpd.mpd},
                          {"segments", mpd.segments},
                          {"valid_segments", mpd.valid_segments},
                          {"spike_samples", mpd.spikes},
                          {"evaluations", mpd.evaluations.size()},
                          {"evaluations_counted", mpd.evaluations_counted},
                          {"evaluation_mean", mpd.evaluation_mean},
                          {"evaluation_min", mpd.evaluation_min},
                          {"evaluation_max", mpd.evaluation_max},
                          {"hurst_fit", a.fit.ok ? nlohmann::json(a.fit.hurst) : nlohmann::json(nullptr)},
                          {"psd_bins", a.psd.q.size()},
                          {"psd_fit_bins", a.fit.bins}};
  });
  if (!keep) std::filesystem::remove(path);
  r.update(made);
  r["samples"] = o.samples;
  r["dx"] = o.dx;
  r["length_m"] = double(o.samples) * o.dx;
  r["evaluation_length"] = o.evaluation_length;
  r["threads"] = o.threads;
  r["file"] = keep ? nlohmann::json(path) : nlohmann::json(nullptr);
  return r;
}

}  // namespace wr::bench
