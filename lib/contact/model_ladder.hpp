#pragma once
// The model ladder (README, "which model for which question"): analytic (microseconds) < spectral (seconds) < FEM
// (minutes). Each model declares validity checks for a contact request; `auto` takes the
// cheapest model whose checks all pass, and every result carries the checks of the model that
// produced it, so a result outside its model's validity is flagged, never silent.
//
// These contact models give the elastostatic friction (a frictionless elastic block interlocked
// with the asperities). The friction a tyre has, viscoelastic hysteresis, is the ladder's other
// rung: lib/friction/friction_scene.hpp (`--model hysteresis` in the sweeps), whose records say
// "mechanism" too, so every number states which mechanism it is.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

enum class ContactModel { analytic, spectral, fem };

struct ContactRequest {
  bool shear = false;         // Problem B (friction) requested
  bool load_control = false;  // a mean pressure (--pressure) instead of a displacement (--uz)
  double pressure = 0;        // Pa, final mean pressure (load control)
  double rms_slope = 0;       // of the obstacle
  double e_star = 0;          // Pa
  int refine = 0;             // FEM contact-face refinement (0: not known / not applicable)
};

struct ValidityCheck {
  std::string name;
  bool passed = false;
  std::string detail;  // the numbers or the reason
  // False for accuracy flags that no other model would fix (the result is flagged, but `auto`
  // keeps the model).
  bool decides_model = true;
};

// Small-slope limit of the spectral model (rms slope). Provisional: the requirement's definition of a
// small-slope scene; the FEM comparison over slopes is to refine it.
constexpr double kSpectralSlopeLimit = 0.2;
// Upper end of the low-pressure regime in which the analytic theories apply (A/A0).
constexpr double kAnalyticAreaLimit = 0.1;

constexpr const char* kElastostaticMechanism =
    "elastostatic: the static resistance of a frictionless elastic block interlocked with the asperities (not a tyre's "
    "friction)";

const char* model_name(ContactModel m);
// Throws std::invalid_argument for an unknown name ("auto" is not a model).
ContactModel parse_model(const std::string& name);

std::vector<ValidityCheck> validity_checks(ContactModel m, const ContactRequest& r);
bool all_passed(const std::vector<ValidityCheck>& checks);

// {model, mechanism, valid, chosen_by ("user", "auto", "sweep"), checks: [{check, passed, detail}]}: the
// record every contact result carries.
nlohmann::json validity_json(ContactModel m, const std::vector<ValidityCheck>& checks, const std::string& chosen_by);

struct ModelChoice {
  bool found = false;
  ContactModel model = ContactModel::fem;
  std::vector<std::pair<ContactModel, std::vector<ValidityCheck>>> considered;  // cheapest first
};
// The cheapest model whose model-deciding checks pass; `found` false when none does.
ModelChoice choose_model(const ContactRequest& r);

}  // namespace wr
