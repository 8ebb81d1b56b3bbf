#include "lib/friction/skid_at_speed.hpp"

#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"
#include "lib/core/parallel.hpp"
#include "lib/flow/effective_medium.hpp"
#include "lib/friction/load_separation.hpp"
#include "lib/friction/squeeze_out.hpp"

namespace wr {
namespace {

constexpr double kKmh = 3.6;
constexpr double kFirstContactShare = 0.01, kDrainedShare = 0.9;

std::vector<double> skid_speeds() {
  std::vector<double> v;
  for (int s = 20; s <= 100; s += 5) v.push_back(s / kKmh);
  return v;
}

SqueezeHistory squeeze_at(const LoadSeparation& ls, const FrictionOptions& opt, const FilmScene& film) {
  const double rms = ls.rms_height(), ac = film.critical_contact;
  SqueezeLaw law;
  law.separation = [&ls](double p) { return ls.separation(p); };
  law.contact = [&ls](double p) { return ls.contact_fraction(p); };
  law.conductance = [rms, ac](double u, double A) { return effective_medium_conductance({A, u, rms}, ac); };
  SqueezeSetup s;
  s.pressure = opt.pressure;
  s.viscosity = water_viscosity(opt.temperature);
  s.drainage_length = film.test.drainage_length;
  s.initial_separation = film.test.water_film;
  return SqueezeHistory(law, s);
}

}  // namespace

SqueezeHistory film_squeeze(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                            const FilmScene& film, double v) {
  const LoadSeparation ls(psd, compound, v, opt.temperature, opt.points_per_decade);
  return squeeze_at(ls, opt, film);
}

FilmPoint film_friction(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                        const FilmScene& film, double v, double mu_h) {
  const LoadSeparation ls(psd, compound, v, opt.temperature, opt.points_per_decade);
  const SqueezeHistory h = squeeze_at(ls, opt, film);
  FilmPoint p;
  p.v = v;
  p.mu_hysteresis = mu_h;
  p.patch_time = film.test.patch_length / v;
  p.load_share = h.mean_load_share(p.patch_time);
  p.mu_viscous = water_viscosity(opt.temperature) * v * h.mean_inverse_film(p.patch_time) / opt.pressure;
  p.mu = mu_h * p.load_share + p.mu_viscous;
  p.drain_time = h.time_to_share(kDrainedShare);
  p.contact_time = h.time_to_share(kFirstContactShare);
  p.equilibrium_separation = ls.separation(opt.pressure);
  p.equilibrium_contact = ls.contact_fraction(opt.pressure);
  p.final_separation = h.at(p.patch_time).separation;
  p.trapped = h.trapped();
  if (!std::isfinite(p.mu)) throw NumericalError("", "non-finite wet friction at v = " + number_text(v) + " m/s");
  return p;
}

std::pair<double, double> fit_speed_constant(const std::vector<double>& s, const std::vector<double>& mu) {
  const std::size_t n = s.size();
  if (n < 2 || mu.size() != n) throw std::invalid_argument("fit_speed_constant: two or more points");
  double ms = 0, ml = 0;
  for (std::size_t i = 0; i < n; ++i) ms += s[i] / n, ml += std::log(mu[i]) / n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) sxx += (s[i] - ms) * (s[i] - ms), sxy += (s[i] - ms) * (std::log(mu[i]) - ml);
  const double slope = sxy / sxx;
  double rss = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = std::log(mu[i]) - (ml + slope * (s[i] - ms));
    rss += r * r;
  }
  const double sp = slope < 0 ? -1 / slope : std::numeric_limits<double>::infinity();
  return {sp, std::sqrt(rss / n)};
}

double hydroplaning_speed(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                          const FilmScene& film) {
  // v = Lc / t_1%(v): t_1% grows with v (stiffer rubber, larger separations), so the map
  // v -> Lc / t(v) is decreasing and the iteration in ln v is a bisection on v - Lc / t(v).
  auto excess = [&](double v) {
    const LoadSeparation ls(psd, compound, v, opt.temperature, opt.points_per_decade);
    const double t = squeeze_at(ls, opt, film).time_to_share(kFirstContactShare);
    return v - film.test.patch_length / t;  // t = 0: -inf (contact at once); t = inf: v
  };
  double lo = 0.1, hi = 1000;  // m/s
  if (excess(hi) < 0) return std::numeric_limits<double>::infinity();
  if (excess(lo) > 0) return lo * kKmh;
  for (int it = 0; it < 40 && hi / lo > 1.001; ++it) {
    const double mid = std::sqrt(lo * hi);
    (excess(mid) < 0 ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi) * kKmh;
}

SkidCurve skid_curve(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                     const FilmScene& film, const std::vector<double>& speeds,
                     const std::function<std::vector<double>(const std::vector<double>&)>& hysteresis) {
  check_water_film(film.test.water_film, "--water-film");
  std::vector<double> all = speeds;
  const std::vector<double> skid = skid_speeds();
  all.insert(all.end(), skid.begin(), skid.end());
  all.push_back(film.test.slip_speed);
  all.push_back(60 / kKmh);
  const std::vector<double> mu_h = hysteresis(all);
  std::vector<FilmPoint> pts(all.size());
  parallel_chunks(all.size(), all.size(), opt.threads, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) pts[i] = film_friction(psd, compound, opt, film, all[i], mu_h[i]);
  });
  SkidCurve c;
  c.points.assign(pts.begin(), pts.begin() + speeds.size());
  c.skid.assign(pts.begin() + speeds.size(), pts.begin() + speeds.size() + skid.size());
  c.at_test = pts[pts.size() - 2];
  c.sn = 100 * c.at_test.mu;
  c.fr60 = pts.back().mu;
  std::vector<double> s_kmh, mu;
  for (const FilmPoint& p : c.skid)
    if (p.mu > 0) s_kmh.push_back(p.v * kKmh), mu.push_back(p.mu);
  if (s_kmh.size() >= 2) std::tie(c.sp_kmh, c.sp_fit_rms) = fit_speed_constant(s_kmh, mu);
  c.hydroplaning_kmh = hydroplaning_speed(psd, compound, opt, film);
  const SqueezeHistory h = film_squeeze(psd, compound, opt, film, film.test.slip_speed);
  const std::size_t n = h.nodes().size(), stride = (n + 199) / 200;
  for (std::size_t k = 0; k < n; k += stride) c.squeeze_at_test.push_back(h.nodes()[k]);
  if (n > 0 && (n - 1) % stride != 0) c.squeeze_at_test.push_back(h.nodes().back());
  return c;
}

}  // namespace wr
