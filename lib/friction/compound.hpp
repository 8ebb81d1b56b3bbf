#pragma once
// A rubber compound's linear viscoelasticity: the complex Young's modulus E(omega, T) of a
// master curve at a reference temperature, as a Prony series (generalized Maxwell model), shifted
// in frequency by the WLF equation. The input of Persson's hysteresis friction (thesis eq. 3.170).
//
// Units: Pa, s, rad/s, degrees Celsius (temperature differences in K).
//   E(omega, Tref) = E_r + sum_i dE_i * i omega tau_i / (1 + i omega tau_i)
//   log10 aT = -C1 (T - Tref) / (C2 + T - Tref),  E(omega, T) = E(omega aT, Tref)
// (or Arrhenius, "arrhenius": {"activation_energy_j_mol": Ea} in place of "wlf":
//   log10 aT = Ea / (R ln 10) (1/T - 1/Tref), T in K)
// so E'(0) = E_r (rubbery plateau), E'(inf) = E_r + sum dE_i (glassy), and each term's loss
// E'' = dE_i omega tau_i / (1 + (omega tau_i)^2) peaks at omega tau_i = 1 with dE_i / 2.
//
// File format (JSON):
//   {"name": "...", "source": "...", "synthetic": false,
//    "reference_temperature_c": 20, "wlf": {"c1": 8.86, "c2_k": 101.6}, "poisson": 0.5,
//    "prony": {"e_relaxed_pa": 3e6, "terms": [{"tau_s": 1e-6, "de_pa": 1e8}, ...]},
//    "thermal": {"density_kg_m3": 1200, "specific_heat_j_kg_k": 1500, "conductivity_w_m_k": 0.25}}
// or, instead of "prony", a measured master curve at Tref:
//    "table": {"omega_rad_s": [...], "storage_pa": [...], "loss_pa": [...]}
// which is checked for causality and used through its Prony fit (lib/friction/modulus_table).
// "synthetic" and "thermal" are optional (thermal: needed by the flash temperature).
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

struct PronyTerm {
  double tau = 0;  // s, > 0
  double de = 0;   // Pa, >= 0
};

struct ThermalProperties {
  double density = 0;        // kg/m^3
  double specific_heat = 0;  // J/(kg K)
  double conductivity = 0;   // W/(m K)
};

struct Compound {
  std::string name, source;
  bool synthetic = false;  // not fitted to a measured master curve: say so wherever it appears
  double reference_temperature = 20;  // deg C
  double wlf_c1 = 8.86, wlf_c2 = 101.6;  // -, K
  // Arrhenius instead of WLF (a compound above Tg + 100 K, or a filler's own shift):
  // log10 aT = Ea / (R ln 10) (1/T - 1/Tref), T in K; J/mol, > 0. Absent: WLF.
  std::optional<double> arrhenius_energy;
  double poisson = 0.5;
  double e_relaxed = 0;  // Pa, > 0
  std::vector<PronyTerm> terms;
  std::optional<ThermalProperties> thermal;
  // "prony" or "table" (then the terms are the causal fit of the table's rows, whose largest
  // relative misfit is table_misfit).
  std::string form = "prony";
  std::size_t table_rows = 0;
  double table_misfit = 0;

  // log10 of the WLF shift factor aT at `temperature` (deg C); InputError when the temperature is
  // at or below Tref - C2, where the WLF equation has its pole.
  double log10_shift(double temperature) const;
  // Complex Young's modulus at angular frequency omega >= 0 (rad/s) and `temperature` (deg C).
  std::complex<double> modulus(double omega, double temperature) const;
  // The same at the reference temperature (no shift).
  std::complex<double> modulus_at_reference(double omega) const;
  double glassy_modulus() const;  // E_r + sum dE_i, Pa
};

// The friction model's cost is linear in the Prony terms (and the flash temperature's more than
// that): a file with more is refused before any work. share/compounds has 37; a table's fit makes
// at most 3 per decade over kMaxTableDecades + 2 decades.
constexpr std::size_t kMaxPronyTerms = 1000;
// Relaxation times a file may give: rubber's span 1e-12 to 1e6 s at any reference temperature;
// beyond these bounds omega tau leaves the doubles at frequencies the friction model uses.
constexpr double kMinTau = 1e-40, kMaxTau = 1e40;

// Every constraint of the file format, InputError(source, "key: problem") on the first broken one.
void check_compound(const Compound& c, const std::string& source);
// Reads and checks a compound JSON file (InputError naming the file and the key at fault).
Compound read_compound_json(const std::string& path);
// The same on the file's text (`source` names it in messages).
Compound parse_compound_json(const std::string& text, const std::string& source);
Compound compound_from_json(const nlohmann::json& j, const std::string& source);
nlohmann::json compound_to_json(const Compound& c);

}  // namespace wr
