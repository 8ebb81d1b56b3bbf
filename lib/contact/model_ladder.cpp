#include "lib/contact/model_ladder.hpp"

#include <cstdio>
#include <stdexcept>

#include "lib/analytic/contact_theory.hpp"

namespace wr {
namespace {

std::string fmt(const char* f, double a, double b) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

}  // namespace

const char* model_name(ContactModel m) {
  switch (m) {
    case ContactModel::analytic: return "analytic";
    case ContactModel::spectral: return "spectral";
    case ContactModel::fem: return "fem";
  }
  return "?";
}

ContactModel parse_model(const std::string& name) {
  if (name == "analytic") return ContactModel::analytic;
  if (name == "spectral") return ContactModel::spectral;
  if (name == "fem") return ContactModel::fem;
  throw std::invalid_argument("unknown contact model '" + name + "' (analytic, spectral, fem or auto)");
}

std::vector<ValidityCheck> validity_checks(ContactModel m, const ContactRequest& r) {
  std::vector<ValidityCheck> c;
  switch (m) {
    case ContactModel::analytic: {
      c.push_back({"normal load only", !r.shear, r.shear ? "the theories give no friction" : "no shear requested"});
      c.push_back({"load control", r.load_control,
                   r.load_control ? "mean pressure given" : "the theories need a mean pressure (--pressure), not --uz"});
      if (r.load_control && r.rms_slope > 0 && r.e_star > 0) {
        const double sigma = r.pressure / (r.e_star * r.rms_slope), area = persson_area_fraction(sigma);
        c.push_back({"low pressure", area <= kAnalyticAreaLimit,
                     fmt("Persson A/A0 %.3g at the final load, limit %.3g", area, kAnalyticAreaLimit)});
      }
      break;
    }
    case ContactModel::spectral:
      c.push_back({"small slopes", r.rms_slope <= kSpectralSlopeLimit,
                   fmt("rms slope %.3g, limit %.3g", r.rms_slope, kSpectralSlopeLimit)});
      if (r.shear)
        c.push_back({"lateral finiteness", false,
                     "a laterally periodic layer is translation invariant: its friction is 0 by construction "
                     "(mu = dE/dux); the finite block's friction needs the FEM"});
      else if (!r.load_control)
        c.push_back({"lateral finiteness", false,
                     "under --uz the periodic layer is in uniaxial strain (modulus M) where the block's free sides "
                     "let it bulge (modulus E): loads differ by up to M/E; give --pressure to compare at equal load"});
      else
        c.push_back({"lateral finiteness", true, "load control: contact statistics at a given mean pressure"});
      break;
    case ContactModel::fem:
      c.push_back({"displacement control", !r.load_control,
                   r.load_control ? "the FEM block is pressed by --uz, not by a pressure" : "--uz given"});
      // At refine 1 every face node sits above a vertex of the triangulated obstacle, where its
      // normal is undefined, and the friction of a frictionless contact follows the chosen
      // normal: on a 32 x 32 scene mu was 0.008 (smooth normals) or 0.09 (facet normals) at
      // refine 1 and 0.0045 / 0.034 at refine 2, 0.0039 (smooth) at refine 4.
      if (r.shear && r.refine > 0)
        c.push_back({"friction resolved", r.refine >= 2,
                     r.refine >= 2 ? "refine " + std::to_string(r.refine) + " (face nodes inside the obstacle's facets)"
                                   : "refine 1: mu depends on the contact-normal model at the obstacle's vertices; use "
                                     "--refine 2 or more",
                     false});
      break;
  }
  return c;
}

bool all_passed(const std::vector<ValidityCheck>& checks) {
  for (const auto& c : checks)
    if (!c.passed) return false;
  return true;
}

ModelChoice choose_model(const ContactRequest& r) {
  ModelChoice choice;
  for (ContactModel m : {ContactModel::analytic, ContactModel::spectral, ContactModel::fem}) {
    choice.considered.emplace_back(m, validity_checks(m, r));
    bool ok = true;
    for (const auto& c : choice.considered.back().second) ok = ok && (c.passed || !c.decides_model);
    if (ok) {
      choice.found = true;
      choice.model = m;
      break;
    }
  }
  return choice;
}

nlohmann::json validity_json(ContactModel m, const std::vector<ValidityCheck>& checks, const std::string& chosen_by) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& v : checks) list.push_back({{"check", v.name}, {"passed", v.passed}, {"detail", v.detail}});
  return {{"model", model_name(m)},
          {"mechanism", kElastostaticMechanism},
          {"valid", all_passed(checks)},
          {"chosen_by", chosen_by},
          {"checks", list}};
}

}  // namespace wr
