#include "lib/friction/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

#include "lib/core/parallel.hpp"

namespace wr {
namespace {

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double x = p * (v.size() - 1);
  const std::size_t k = static_cast<std::size_t>(x);
  return k + 1 < v.size() ? v[k] + (x - k) * (v[k + 1] - v[k]) : v.back();
}

double value_at(const InputRange& r, double u) {  // u in [0, 1]
  return r.logarithmic ? r.low * std::pow(r.high / r.low, u) : r.low + u * (r.high - r.low);
}

}  // namespace

std::vector<InputRange> default_ranges(const SkidInputs& in) {
  std::vector<InputRange> r = {
      {"pressure", in.options.pressure * 2 / 3, in.options.pressure * 4 / 3, false},
      {"temperature", in.options.temperature - 10, in.options.temperature + 10, false},
      {"water_film", in.film.test.water_film / 2, std::min(kMaxWaterFilm, in.film.test.water_film * 2), true},
      {"q1", in.dry.q_end / 3, in.dry.q_end * 3, true}};
  if (in.compound.synthetic) r.push_back({"compound_shift", -0.5, 0.5, false});
  return r;
}

double skid_number_at(const SkidInputs& in, const std::vector<std::pair<std::string, double>>& values) {
  FrictionOptions opt = in.options;
  opt.threads = 1;
  FilmScene film = in.film;
  Compound compound = in.compound;
  RoughnessSpectrum dry = in.dry, hyst = in.hysteresis;
  for (const auto& [name, v] : values) {
    if (name == "pressure") opt.pressure = v;
    else if (name == "temperature") opt.temperature = v;
    else if (name == "water_film") film.test.water_film = v;
    else if (name == "q1") dry.q_end = hyst.q_end = std::max(v, dry.q_start * 1.01);  // along the fitted extension
    else if (name == "compound_shift") {
      // the master curve moved by v decades in frequency: every relaxation time times 10^-v
      for (PronyTerm& t : compound.terms) t.tau *= std::pow(10.0, -v);
    } else {
      throw std::invalid_argument("skid_number_at: unknown input " + name);
    }
  }
  const double v = film.test.slip_speed;
  const double mu_h = in.hysteresis_scale * hysteresis_friction(hyst, compound, v, opt).mu;
  return 100 * film_friction(dry, compound, opt, film, v, mu_h).mu;
}

SkidBand skid_number_band(const SkidInputs& in, const UncertaintySetup& st) {
  if (st.samples < 2) throw std::invalid_argument("skid_number_band: at least 2 samples");
  SkidBand b;
  const std::size_t k = st.ranges.size();
  // jobs: the nominal, 2 per input (tornado), then the Latin hypercube
  std::vector<std::vector<std::pair<std::string, double>>> jobs(1);
  for (const InputRange& r : st.ranges) {
    jobs.push_back({{r.name, r.low}});
    jobs.push_back({{r.name, r.high}});
  }
  std::mt19937_64 rng(st.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<int>> strata(k, std::vector<int>(st.samples));
  for (auto& s : strata) {
    std::iota(s.begin(), s.end(), 0);
    std::shuffle(s.begin(), s.end(), rng);
  }
  for (int i = 0; i < st.samples; ++i) {
    std::vector<std::pair<std::string, double>> job;
    for (std::size_t j = 0; j < k; ++j)
      job.push_back({st.ranges[j].name, value_at(st.ranges[j], (strata[j][i] + unit(rng)) / st.samples)});
    jobs.push_back(job);
  }
  std::vector<double> sn(jobs.size());
  parallel_chunks(jobs.size(), jobs.size(), in.options.threads, [&](std::size_t, std::size_t a, std::size_t e) {
    for (std::size_t i = a; i < e; ++i) sn[i] = skid_number_at(in, jobs[i]);
  });
  b.evaluations = static_cast<int>(jobs.size());
  b.nominal = sn[0];
  for (std::size_t j = 0; j < k; ++j)
    b.tornado.push_back({st.ranges[j].name, st.ranges[j].low, st.ranges[j].high, sn[1 + 2 * j], sn[2 + 2 * j]});
  std::sort(b.tornado.begin(), b.tornado.end(), [](const TornadoRow& x, const TornadoRow& y) {
    return std::abs(x.sn_high - x.sn_low) > std::abs(y.sn_high - y.sn_low);
  });
  b.samples.assign(sn.begin() + 1 + 2 * k, sn.end());
  b.p05 = percentile(b.samples, 0.05);
  b.p95 = percentile(b.samples, 0.95);
  b.min = *std::min_element(b.samples.begin(), b.samples.end());
  b.max = *std::max_element(b.samples.begin(), b.samples.end());
  return b;
}

}  // namespace wr
