#include "lib/friction/master_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/core/errors.hpp"
#include "lib/core/number_text.hpp"

namespace wr {
namespace {

constexpr double kGas = 8.314462618;  // J/(mol K)
constexpr double kBinDecades = 0.1;

struct LogCurve {
  std::vector<double> x, y1, y2;  // log10 omega, log10 E', log10 E''
};

LogCurve log_curve(const Isotherm& iso, double vertical) {
  LogCurve c;
  for (std::size_t i = 0; i < iso.omega.size(); ++i) {
    c.x.push_back(std::log10(iso.omega[i]));
    c.y1.push_back(std::log10(iso.storage[i] * vertical));
    c.y2.push_back(std::log10(iso.loss[i] * vertical));
  }
  return c;
}

// y(x) by linear interpolation; x inside [x.front(), x.back()].
double at(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const auto it = std::lower_bound(xs.begin(), xs.end(), x);
  if (it == xs.begin()) return ys.front();
  if (it == xs.end()) return ys.back();
  const std::size_t k = static_cast<std::size_t>(it - xs.begin());
  const double t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + t * (ys[k] - ys[k - 1]);
}

// Mean square mismatch of the colder curve a, shifted by +d in log frequency, against b over
// their overlap (points of both); +inf with less than kMinOverlapDecades of overlap.
double mismatch(const LogCurve& a, const LogCurve& b, double d) {
  const double lo = std::max(a.x.front() + d, b.x.front()), hi = std::min(a.x.back() + d, b.x.back());
  if (hi - lo < kMinOverlapDecades) return std::numeric_limits<double>::infinity();
  double s = 0;
  int n = 0;
  for (std::size_t i = 0; i < a.x.size(); ++i) {
    const double x = a.x[i] + d;
    if (x < lo || x > hi) continue;
    s += std::pow(a.y1[i] - at(b.x, b.y1, x), 2) + std::pow(a.y2[i] - at(b.x, b.y2, x), 2);
    n += 2;
  }
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    const double x = b.x[i] - d;
    if (b.x[i] < lo || b.x[i] > hi) continue;
    s += std::pow(b.y1[i] - at(a.x, a.y1, x), 2) + std::pow(b.y2[i] - at(a.x, a.y2, x), 2);
    n += 2;
  }
  return n ? s / n : std::numeric_limits<double>::infinity();
}

// Golden-section minimum of f on [a, b].
template <class F>
double golden(F f, double a, double b, int iterations = 80) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  for (int i = 0; i < iterations; ++i) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

// The colder isotherm's shift d against the warmer one, and the rms mismatch there.
std::pair<double, double> relative_shift(const LogCurve& cold, const LogCurve& warm, const std::string& what) {
  const double span = (cold.x.back() - cold.x.front()) + (warm.x.back() - warm.x.front());
  const double lo = warm.x.front() - cold.x.back(), hi = warm.x.back() - cold.x.front();
  double best = 0, fbest = std::numeric_limits<double>::infinity();
  const int steps = std::max(200, static_cast<int>(span / 0.005));
  for (int i = 0; i <= steps; ++i) {
    const double d = lo + (hi - lo) * i / steps, f = mismatch(cold, warm, d);
    if (f < fbest) fbest = f, best = d;
  }
  if (!std::isfinite(fbest)) throw InputError(what, "do not overlap in frequency by " + number_text(kMinOverlapDecades) + " decades at any shift");
  const double step = (hi - lo) / steps;
  best = golden([&](double d) { return mismatch(cold, warm, d); }, best - step, best + step);
  const double rms = std::sqrt(mismatch(cold, warm, best));
  // the best shift at the edge of what overlaps, or a poor match: the curves do not superpose there
  const bool edge = mismatch(cold, warm, best - 2 * step) == std::numeric_limits<double>::infinity() ||
                    mismatch(cold, warm, best + 2 * step) == std::numeric_limits<double>::infinity();
  if (!std::isfinite(rms))
    throw InputError(what, "do not overlap in frequency by " + number_text(kMinOverlapDecades) +
                               " decades at the shift that matches them best");
  if (rms > kMaxMismatchDecades || edge)
    throw InputError(what, "do not overlap: the best shift (" + number_text(best) + " decades) leaves an rms mismatch of " +
                               number_text(rms) + " decades in log E', log E''" +
                               (edge ? " at the edge of their common frequency range" : "") +
                               "; measure at temperatures closer together or over a wider frequency range");
  return {best, rms};
}

struct LawFit {
  double c1 = 0, c2 = 0, ea = 0, rms = 0;
};

double wlf(double c1, double c2, double dt) { return -c1 * dt / (c2 + dt); }

LawFit fit_wlf(const std::vector<double>& t, const std::vector<double>& la, double tr, const std::string& source) {
  const double tmin = *std::min_element(t.begin(), t.end());
  const double c2_lo = std::max(1e-3, tr - tmin + 1e-3), c2_hi = 5000;
  auto c1_of = [&](double c2) {
    double num = 0, den = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double g = (t[i] - tr) / (c2 + t[i] - tr);
      num -= la[i] * g, den += g * g;
    }
    return den > 0 ? num / den : 0.0;
  };
  auto sse = [&](double c2) {
    const double c1 = c1_of(c2);
    double s = 0;
    for (std::size_t i = 0; i < t.size(); ++i) s += std::pow(la[i] - wlf(c1, c2, t[i] - tr), 2);
    return s;
  };
  // scan in log C2, then golden section around the best
  double best = c2_lo, fbest = std::numeric_limits<double>::infinity();
  const int n = 400;
  for (int i = 0; i <= n; ++i) {
    const double c2 = c2_lo * std::pow(c2_hi / c2_lo, double(i) / n), f = sse(c2);
    if (f < fbest) fbest = f, best = c2;
  }
  const double r = std::pow(c2_hi / c2_lo, 1.0 / n);
  const double c2 = std::exp(golden([&](double l) { return sse(std::exp(l)); }, std::log(std::max(c2_lo, best / r)),
                                    std::log(std::min(c2_hi, best * r))));
  LawFit f;
  f.c2 = c2;
  f.c1 = c1_of(c2);
  f.rms = std::sqrt(sse(c2) / t.size());
  if (!(f.c1 > 0)) throw InputError(source, "the shift factors do not follow a WLF law (C1 <= 0): colder isotherms must lie at higher reduced frequency");
  return f;
}

LawFit fit_arrhenius(const std::vector<double>& t, const std::vector<double>& la, double tr, const std::string& source) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double z = 1 / (t[i] + 273.15) - 1 / (tr + 273.15);
    num += la[i] * z, den += z * z;
  }
  LawFit f;
  f.ea = num / den * kGas * std::log(10.0);
  double s = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    s += std::pow(la[i] - f.ea / (kGas * std::log(10.0)) * (1 / (t[i] + 273.15) - 1 / (tr + 273.15)), 2);
  f.rms = std::sqrt(s / t.size());
  if (!(f.ea > 0)) throw InputError(source, "the shift factors give a negative activation energy: not an Arrhenius material");
  return f;
}

// The binned master curve: log-averages over kBinDecades of reduced frequency.
ModulusTable bin_master(const DmaData& data, const std::vector<double>& la, const MasterCurveOptions& opt, double tref) {
  struct P {
    double x, y1, y2;
  };
  std::vector<P> pts;
  for (std::size_t i = 0; i < data.isotherms.size(); ++i) {
    const Isotherm& iso = data.isotherms[i];
    const double bt = opt.vertical_shift ? (tref + 273.15) / (iso.temperature + 273.15) : 1.0;
    for (std::size_t k = 0; k < iso.omega.size(); ++k)
      pts.push_back({std::log10(iso.omega[k]) + la[i], std::log10(iso.storage[k] * bt), std::log10(iso.loss[k] * bt)});
  }
  std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.x < b.x; });
  ModulusTable t;
  std::size_t i = 0;
  while (i < pts.size()) {
    const double bin = std::floor(pts[i].x / kBinDecades);
    double sx = 0, s1 = 0, s2 = 0;
    int n = 0;
    for (; i < pts.size() && std::floor(pts[i].x / kBinDecades) == bin; ++i, ++n) sx += pts[i].x, s1 += pts[i].y1, s2 += pts[i].y2;
    t.omega.push_back(std::pow(10.0, sx / n));
    t.storage.push_back(std::pow(10.0, s1 / n));
    t.loss.push_back(std::pow(10.0, s2 / n));
  }
  return t;
}

}  // namespace

double MasterCurve::log10_shift(double temperature) const {
  if (law == ShiftLaw::arrhenius)
    return activation_energy / (kGas * std::log(10.0)) * (1 / (temperature + 273.15) - 1 / (reference_temperature + 273.15));
  return wlf(c1, c2, temperature - reference_temperature);
}

MasterCurve build_master_curve(const DmaData& data, const MasterCurveOptions& opt) {
  const std::vector<Isotherm>& iso = data.isotherms;
  const std::size_t n = iso.size();
  const double tmin = iso.front().temperature, tmax = iso.back().temperature;
  const double tref = opt.reference_temperature.value_or(std::clamp(20.0, tmin, tmax));
  if (!(tref >= tmin - 1e-9 && tref <= tmax + 1e-9))
    throw InputError("--reference-temperature", "must lie within the data's temperatures, " + number_text(tmin) + " ... " +
                                                    number_text(tmax) + " C");
  // the base isotherm: the one nearest Tref
  std::size_t base = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (std::abs(iso[i].temperature - tref) < std::abs(iso[base].temperature - tref)) base = i;
  std::vector<LogCurve> curves;
  for (const Isotherm& s : iso)
    curves.push_back(log_curve(s, opt.vertical_shift ? (iso[base].temperature + 273.15) / (s.temperature + 273.15) : 1.0));
  std::vector<double> d(n, 0.0), rms(n, 0.0);  // d[i]: isotherm i against i + 1
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const std::string what = data.source + ": isotherms " + number_text(iso[i].temperature) + " C and " +
                             number_text(iso[i + 1].temperature) + " C";
    std::tie(d[i], rms[i]) = relative_shift(curves[i], curves[i + 1], what);
  }
  std::vector<double> la(n, 0.0), temps(n);
  for (std::size_t i = base; i-- > 0;) la[i] = la[i + 1] + d[i];
  for (std::size_t i = base + 1; i < n; ++i) la[i] = la[i - 1] - d[i - 1];
  for (std::size_t i = 0; i < n; ++i) temps[i] = iso[i].temperature;
  MasterCurve m;
  m.law = opt.law;
  m.reference_temperature = tref;
  const double tb = iso[base].temperature;
  double la_tref = 0;  // the law's shift at Tref, relative to the base isotherm
  if (opt.law == ShiftLaw::wlf) {
    const LawFit f = fit_wlf(temps, la, tb, data.source);
    m.c2 = f.c2 + (tref - tb);
    if (!(m.c2 > 0)) throw InputError("--reference-temperature", "lies below the fitted WLF law's pole");
    m.c1 = f.c1 * f.c2 / m.c2;
    la_tref = wlf(f.c1, f.c2, tref - tb);
    m.fit_rms = f.rms;
  } else {
    const LawFit f = fit_arrhenius(temps, la, tb, data.source);
    m.activation_energy = f.ea;
    la_tref = f.ea / (kGas * std::log(10.0)) * (1 / (tref + 273.15) - 1 / (tb + 273.15));
    m.fit_rms = f.rms;
  }
  for (std::size_t i = 0; i < n; ++i) {
    la[i] -= la_tref;
    m.shifts.push_back({temps[i], la[i], m.log10_shift(temps[i]), rms[i]});
  }
  m.table = bin_master(data, la, opt, tref);
  if (m.table.omega.size() < 4) throw InputError(data.source, "the master curve has fewer than 4 points after binning");
  const double decades = std::log10(m.table.omega.back() / m.table.omega.front());
  if (decades > kMaxTableDecades)
    throw InputError(data.source, "the master curve spans " + number_text(decades) + " decades of reduced frequency; at most " +
                                      number_text(kMaxTableDecades));
  m.prony = causal_prony_fit(m.table, data.source);
  // the loss peak at Tref: scan the Prony E'' over the table's range
  Compound c;
  c.e_relaxed = m.prony.e_relaxed;
  c.terms = m.prony.terms;
  const double a = std::log10(m.table.omega.front()), b = std::log10(m.table.omega.back());
  double peak = 0;
  for (int k = 0; k <= 2000; ++k) {
    const double w = std::pow(10.0, a + (b - a) * k / 2000);
    const std::complex<double> e = c.modulus_at_reference(w);
    if (e.imag() > peak) peak = e.imag(), m.loss_peak_omega = w;
    m.loss_peak_tan_delta = std::max(m.loss_peak_tan_delta, e.imag() / e.real());
  }
  // Tg: the temperature at which that peak sits at 1 Hz, log aT(Tg) = log10(omega_peak / 2 pi)
  const double L = std::log10(m.loss_peak_omega / (2 * M_PI));
  if (m.law == ShiftLaw::wlf) {
    if (m.c1 + L > 0) m.glass_transition = tref - L * m.c2 / (m.c1 + L);
  } else {
    const double inv = 1 / (tref + 273.15) + L * kGas * std::log(10.0) / m.activation_energy;
    if (inv > 0) m.glass_transition = 1 / inv - 273.15;
  }
  return m;
}

Compound compound_from_master(const MasterCurve& m, const std::string& name, const std::string& source, double poisson) {
  Compound c;
  c.name = name;
  c.source = source;
  c.synthetic = false;
  c.reference_temperature = m.reference_temperature;
  if (m.law == ShiftLaw::wlf) {
    c.wlf_c1 = m.c1;
    c.wlf_c2 = m.c2;
  } else {
    c.arrhenius_energy = m.activation_energy;
  }
  c.poisson = poisson;
  c.e_relaxed = m.prony.e_relaxed;
  c.terms = m.prony.terms;
  c.form = "table";
  c.table_rows = m.table.omega.size();
  c.table_misfit = m.prony.max_misfit;
  check_compound(c, source);
  return c;
}

}  // namespace wr
