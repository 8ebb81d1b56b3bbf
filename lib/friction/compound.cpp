#include "lib/friction/compound.hpp"

#include <cmath>

#include "lib/core/errors.hpp"
#include "lib/friction/modulus_table.hpp"
#include "lib/io/input_file.hpp"

namespace wr {
namespace {

// A positive finite number under `key` of `j` (InputError naming source and key otherwise).
double positive(const nlohmann::json& j, const char* key, const std::string& source) {
  if (!j.is_object() || !j.contains(key)) throw InputError(source, std::string("missing key \"") + key + "\"");
  const nlohmann::json& v = j[key];
  if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
    throw InputError(source, std::string("\"") + key + "\" must be a positive number");
  return v.get<double>();
}

double number(const nlohmann::json& j, const char* key, const std::string& source) {
  if (!j.is_object() || !j.contains(key)) throw InputError(source, std::string("missing key \"") + key + "\"");
  const nlohmann::json& v = j[key];
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw InputError(source, std::string("\"") + key + "\" must be a finite number");
  return v.get<double>();
}

std::string text(const nlohmann::json& j, const char* key, const std::string& source) {
  if (!j.contains(key) || !j[key].is_string()) throw InputError(source, std::string("missing text \"") + key + "\"");
  return j[key].get<std::string>();
}

std::vector<double> number_list(const nlohmann::json& j, const char* key, const std::string& source) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_array())
    throw InputError(source, std::string("table: missing list \"") + key + "\"");
  std::vector<double> out;
  for (const auto& v : j[key]) {
    if (!v.is_number()) throw InputError(source, std::string("table.") + key + ": every entry must be a number");
    out.push_back(v.get<double>());
  }
  return out;
}

ModulusTable table_from_json(const nlohmann::json& j, const std::string& source) {
  ModulusTable t;
  t.omega = number_list(j, "omega_rad_s", source);
  t.storage = number_list(j, "storage_pa", source);
  t.loss = number_list(j, "loss_pa", source);
  return t;
}

}  // namespace

double Compound::log10_shift(double temperature) const {
  if (arrhenius_energy) {
    constexpr double kGas = 8.314462618;  // J/(mol K)
    if (!(temperature > -273.15)) throw InputError("--temperature", "must lie above absolute zero");
    return *arrhenius_energy / (kGas * std::log(10.0)) * (1 / (temperature + 273.15) - 1 / (reference_temperature + 273.15));
  }
  const double dt = temperature - reference_temperature;
  if (!(wlf_c2 + dt > 0))
    throw InputError("--temperature", "the WLF shift has its pole at Tref - C2 = " +
                                          std::to_string(reference_temperature - wlf_c2) + " C; give a warmer temperature");
  return -wlf_c1 * dt / (wlf_c2 + dt);
}

std::complex<double> Compound::modulus_at_reference(double omega) const {
  std::complex<double> e(e_relaxed, 0.0);
  for (const PronyTerm& t : terms) {
    const double x = omega * t.tau;
    // dE i x / (1 + i x) = dE (x^2 + i x) / (1 + x^2); above x = 1 divided through by x^2, so
    // that a long relaxation time at a high frequency (x^2 = inf) gives dE, not inf / inf.
    if (x <= 1) e += t.de * std::complex<double>(x * x, x) / (1 + x * x);
    else e += t.de * std::complex<double>(1 / (1 + 1 / (x * x)), 1 / (x + 1 / x));
  }
  return e;
}

std::complex<double> Compound::modulus(double omega, double temperature) const {
  return modulus_at_reference(omega * std::pow(10.0, log10_shift(temperature)));
}

double Compound::glassy_modulus() const {
  double e = e_relaxed;
  for (const PronyTerm& t : terms) e += t.de;
  return e;
}

void check_compound(const Compound& c, const std::string& source) {
  if (!(c.e_relaxed > 0 && std::isfinite(c.e_relaxed))) throw InputError(source, "prony.e_relaxed_pa must be a positive modulus in Pa");
  if (c.terms.empty()) throw InputError(source, "prony.terms: give at least one term (a purely elastic rubber has no hysteresis)");
  if (c.terms.size() > kMaxPronyTerms)
    throw InputError(source, "prony.terms: " + std::to_string(c.terms.size()) + " terms; at most " + std::to_string(kMaxPronyTerms));
  for (std::size_t i = 0; i < c.terms.size(); ++i) {
    const std::string at = "prony.terms[" + std::to_string(i) + "]";
    if (!(c.terms[i].tau >= kMinTau && c.terms[i].tau <= kMaxTau))
      throw InputError(source, at + ".tau_s must be a time in [1e-40, 1e40] s");
    if (!(c.terms[i].de >= 0 && std::isfinite(c.terms[i].de))) throw InputError(source, at + ".de_pa must be a modulus >= 0 Pa");
  }
  if (!std::isfinite(c.glassy_modulus())) throw InputError(source, "prony: the glassy modulus e_relaxed_pa + sum of de_pa overflows");
  if (!(c.poisson > -1 && c.poisson <= 0.5)) throw InputError(source, "poisson must lie in (-1, 0.5]");
  if (c.arrhenius_energy && !(*c.arrhenius_energy > 0 && std::isfinite(*c.arrhenius_energy)))
    throw InputError(source, "arrhenius.activation_energy_j_mol must be a positive energy in J/mol");
  if (!(c.wlf_c1 >= 0 && std::isfinite(c.wlf_c1))) throw InputError(source, "wlf.c1 must be a finite number >= 0");
  if (!(c.wlf_c2 > 0 && std::isfinite(c.wlf_c2))) throw InputError(source, "wlf.c2_k must be positive (K)");
  if (!std::isfinite(c.reference_temperature)) throw InputError(source, "reference_temperature_c must be finite");
  if (c.thermal && !(c.thermal->density > 0 && c.thermal->specific_heat > 0 && c.thermal->conductivity > 0))
    throw InputError(source, "thermal: density, specific heat and conductivity must be positive");
}

Compound compound_from_json(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, "a compound file is a JSON object");
  Compound c;
  c.name = text(j, "name", source);
  c.source = text(j, "source", source);
  if (j.contains("synthetic")) {
    if (!j["synthetic"].is_boolean()) throw InputError(source, "\"synthetic\" must be true or false");
    c.synthetic = j["synthetic"].get<bool>();
  }
  c.reference_temperature = number(j, "reference_temperature_c", source);
  if (j.contains("wlf") == j.contains("arrhenius"))
    throw InputError(source, j.contains("wlf") ? "give the shift law as \"wlf\" or \"arrhenius\", not both"
                                               : "missing key \"wlf\" (or \"arrhenius\")");
  if (j.contains("wlf")) {
    c.wlf_c1 = number(j["wlf"], "c1", source);
    c.wlf_c2 = positive(j["wlf"], "c2_k", source);
  } else {
    c.arrhenius_energy = positive(j["arrhenius"], "activation_energy_j_mol", source);
  }
  c.poisson = number(j, "poisson", source);
  if (j.contains("prony") == j.contains("table"))
    throw InputError(source, "give the master curve as either \"prony\" (a Prony series) or \"table\" (omega, E', E''), not " +
                                 std::string(j.contains("prony") ? "both" : "neither"));
  if (j.contains("prony")) {
    const nlohmann::json& p = j["prony"];
    c.e_relaxed = positive(p, "e_relaxed_pa", source);
    if (!p.contains("terms") || !p["terms"].is_array()) throw InputError(source, "prony.terms must be a list");
    if (p["terms"].size() > kMaxPronyTerms)
      throw InputError(source, "prony.terms: " + std::to_string(p["terms"].size()) + " terms; at most " +
                                   std::to_string(kMaxPronyTerms) + " are read (a few per decade of relaxation time is enough)");
    for (const auto& t : p["terms"]) c.terms.push_back({positive(t, "tau_s", source), number(t, "de_pa", source)});
  } else {
    const ModulusTable table = table_from_json(j["table"], source);
    const PronyFit fit = causal_prony_fit(table, source);
    c.form = "table";
    c.table_rows = table.omega.size();
    c.table_misfit = fit.max_misfit;
    c.e_relaxed = fit.e_relaxed;
    c.terms = fit.terms;
  }
  if (j.contains("thermal")) {
    const nlohmann::json& t = j["thermal"];
    c.thermal = ThermalProperties{positive(t, "density_kg_m3", source), positive(t, "specific_heat_j_kg_k", source),
                                  positive(t, "conductivity_w_m_k", source)};
  }
  check_compound(c, source);
  return c;
}

Compound parse_compound_json(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);  // skips a UTF-8 BOM; refuses text that is not UTF-8
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source, std::string("not valid JSON: ") + e.what());
  }
  return compound_from_json(j, source);
}

Compound read_compound_json(const std::string& path) {
  return parse_compound_json(read_input_file(path, "compound file"), path);
}

nlohmann::json compound_to_json(const Compound& c) {
  nlohmann::json terms = nlohmann::json::array();
  for (const PronyTerm& t : c.terms) terms.push_back({{"tau_s", t.tau}, {"de_pa", t.de}});
  nlohmann::json j = {{"name", c.name},
                      {"source", c.source},
                      {"synthetic", c.synthetic},
                      {"reference_temperature_c", c.reference_temperature},
                      {"poisson", c.poisson},
                      {"prony", {{"e_relaxed_pa", c.e_relaxed}, {"terms", terms}}}};
  if (c.arrhenius_energy)
    j["arrhenius"] = {{"activation_energy_j_mol", *c.arrhenius_energy}};
  else
    j["wlf"] = {{"c1", c.wlf_c1}, {"c2_k", c.wlf_c2}};
  if (c.form == "table") j["table_fit"] = {{"rows", c.table_rows}, {"max_misfit", c.table_misfit}};
  if (c.thermal)
    j["thermal"] = {{"density_kg_m3", c.thermal->density},
                    {"specific_heat_j_kg_k", c.thermal->specific_heat},
                    {"conductivity_w_m_k", c.thermal->conductivity}};
  return j;
}

}  // namespace wr
