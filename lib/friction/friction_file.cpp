#include "lib/friction/friction_file.hpp"

#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/io/hdf5_file.hpp"

namespace wr {
namespace {

void write_curve(Hdf5Writer& w, const std::string& group, const FrictionCurve& c) {
  w.create_group(group);
  std::vector<double> mu, area, rise, extra;
  for (const FrictionPoint& p : c.points) {
    mu.push_back(p.mu);
    area.push_back(p.area_fraction);
    rise.push_back(p.temperature_rise);
    extra.push_back(p.mu_extrapolated);
  }
  w.write_vector(group + "/mu", mu);
  w.write_vector(group + "/area_fraction", area);
  w.write_vector(group + "/temperature_rise", rise);
  w.write_vector(group + "/mu_extrapolated", extra);
  w.write_attr(group, "sn64", c.sn64);
  w.write_attr(group, "peak_mu", c.peak_mu);
  w.write_attr(group, "peak_v", c.peak_v);
}

}  // namespace

void write_friction_file(const std::string& path, const FrictionRun& r, const nlohmann::json& summary,
                         const nlohmann::json& provenance) {
  Hdf5Writer w(path);
  std::vector<double> speeds;
  for (const FrictionPoint& p : r.dry.points) speeds.push_back(p.v);
  w.write_vector("/speeds", speeds);
  write_curve(w, "/dry", r.dry);
  if (r.wet_homogeneous) write_curve(w, "/wet_homogeneous", *r.wet_homogeneous);
  if (r.wet_local) write_curve(w, "/wet_local", *r.wet_local);
  w.create_group("/spectrum");
  std::vector<double> q, C;
  const RoughnessSpectrum& s = r.dry_spectrum;
  for (double x : s.q)
    if (x <= s.q_measured) {
      q.push_back(x);
      C.push_back(s(x));
    }
  if (s.extrapolated())
    for (int k = 1; k <= 40; ++k) {
      const double x = s.q_measured * std::pow(s.q_end / s.q_measured, k / 40.0);
      q.push_back(x);
      C.push_back(s(x));
    }
  w.write_vector("/spectrum/q", q);
  w.write_vector("/spectrum/C", C);
  w.write_attr("/spectrum", "q_measured", s.q_measured);
  w.write_text("/summary", summary.dump());
  w.write_attr("/", "provenance", provenance.dump());
  w.commit();
}

}  // namespace wr

namespace wr {

nlohmann::json read_friction_summary(const std::string& path) {
  Hdf5Reader r(path);
  if (!r.has_dataset("/summary") || !r.has_group("/dry"))
    throw InputError(path, "not a friction result (written by `wetroad friction --out`)");
  try {
    nlohmann::json j = nlohmann::json::parse(r.read_text("/summary"));
    if (j.value("model", "") != "hysteresis") throw InputError(path, "not a friction result (model is not hysteresis)");
    return j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("corrupt /summary: ") + e.what());
  }
}

}  // namespace wr
