#include "lib/contact/area_load_fits.hpp"

#include <stdexcept>

namespace wr {

NormalCurve normal_curve(const std::vector<ContactStep>& steps) {
  NormalCurve c;
  for (const auto& st : steps)
    if (st.converged && st.ux == 0 && st.sigma_star > 0) {
      c.sigma_star.push_back(st.sigma_star);
      c.area.push_back(st.area_fraction);
    }
  return c;
}

AreaLoadFits area_load_fits(const std::vector<ContactStep>& steps) {
  const NormalCurve c = normal_curve(steps);
  AreaLoadFits f;
  if (c.sigma_star.empty()) return f;
  f.any = true;
  // The low-pressure regression of sec. 5.2.3 needs no minimum: any step below 15 % counts.
  f.low = fit_low_pressure_kappa(c.sigma_star, c.area);
  if (c.sigma_star.size() < 4) return f;
  try {
    f.quartic = fit_quartic_area(c.sigma_star, c.area);
    if (f.quartic->kappa > 0) f.yam = fit_yam(c.sigma_star, c.area, f.quartic->kappa);
  } catch (const std::invalid_argument&) {
    f.quartic.reset();
    f.yam.reset();
  }
  return f;
}

nlohmann::json quartic_json(const QuarticAreaFit& q) {
  return {{"Pi", q.pi}, {"Omega", q.omega}, {"Lambda", q.lambda}, {"kappa", q.kappa}, {"r2", q.r2}};
}

nlohmann::json area_load_fits_json(const AreaLoadFits& f, double central_ratio) {
  if (!f.any) return nullptr;
  nlohmann::json low = {{"kappa", f.low.kappa}, {"points", f.low.points}, {"max_area_fraction", f.low.max_area}};
  if (central_ratio > 0) low["kappa_central_slope"] = f.low.kappa * central_ratio;
  if (!f.quartic) return nlohmann::json{{"low_pressure", low}};
  nlohmann::json q = quartic_json(*f.quartic);
  q["eps_1e4"] = 1e4 * (1 - f.quartic->r2);
  nlohmann::json j = {{"quartic", q}, {"low_pressure", low}};
  if (f.yam) j["yam"] = {{"kappa", f.yam->kappa}, {"beta", f.yam->beta}, {"mu", f.yam->mu}, {"rms_error", f.yam->rms_error}};
  return j;
}

}  // namespace wr
