#pragma once
// From DMA isotherms to a compound: time-temperature superposition (Ferry, Viscoelastic
// Properties of Polymers, 3rd ed., ch. 11), a shift law fitted to the shift factors, and the
// causal Prony series of the master curve (lib/friction/modulus_table.hpp).
//
// 1. Horizontal shift factors by overlap of adjacent isotherms: the relative shift d of the
//    colder isotherm against the warmer one minimises the mean square mismatch of log E' and
//    log E'' over their overlap in log frequency (E'' carries the information where E' is a
//    plateau); at least kMinOverlapDecades of overlap, else the pair is refused as not
//    overlapping, as is a best mismatch above kMaxMismatchDecades rms. Shifts accumulate from the
//    isotherm nearest the reference temperature. Optional vertical shift bT = T0/T (absolute
//    temperatures; the density's change is neglected) before shifting.
// 2. The shift law fitted to log aT(T) by least squares: WLF log aT = -C1 (T - Tr)/(C2 + T - Tr)
//    (C1 in closed form for each C2, C2 by a scan then golden section) or Arrhenius
//    log aT = Ea/(R ln 10) (1/T - 1/Tr) (linear); re-referenced exactly to the reference
//    temperature asked for (WLF: C2' = C2 + Tr' - Tr, C1' = C1 C2 / C2').
// 3. The master curve at Tref: every point at its reduced frequency omega aT (measured shifts),
//    averaged in log over 0.1-decade bins, fitted by the causal Prony series with the
//    Kramers-Kronig check (refused beyond 10 % misfit).
// 4. The loss peak at Tref (the maximum of E'' of the Prony series) and the glass transition as
//    the temperature at which that peak sits at 1 Hz (the DMA convention of the E'' peak at 1 Hz).
#include <optional>
#include <string>
#include <vector>

#include "lib/friction/compound.hpp"
#include "lib/friction/dma_data.hpp"
#include "lib/friction/modulus_table.hpp"

namespace wr {

constexpr double kMinOverlapDecades = 0.3;
constexpr double kMaxMismatchDecades = 0.05;

enum class ShiftLaw { wlf, arrhenius };

struct MasterCurveOptions {
  std::optional<double> reference_temperature;  // deg C; absent: the isotherm nearest 20 C
  ShiftLaw law = ShiftLaw::wlf;
  bool vertical_shift = false;
};

struct ShiftRow {
  double temperature = 0;   // deg C
  double log_at = 0;        // measured by overlap, relative to Tref
  double log_at_fit = 0;    // the fitted law's
  double mismatch = 0;      // rms of log E', log E'' against the warmer neighbour (decades; 0 for the warmest)
};

struct MasterCurve {
  double reference_temperature = 20;
  ShiftLaw law = ShiftLaw::wlf;
  double c1 = 0, c2 = 0;             // WLF (-, K)
  double activation_energy = 0;      // J/mol (Arrhenius)
  double fit_rms = 0;                // decades: rms of log aT - the law
  std::vector<ShiftRow> shifts;      // ascending temperature
  ModulusTable table;                // the binned master curve at Tref
  PronyFit prony;
  double loss_peak_omega = 0;        // rad/s at Tref
  double loss_peak_tan_delta = 0;
  std::optional<double> glass_transition;  // deg C (E'' peak at 1 Hz); absent beyond the law's range
  double log10_shift(double temperature) const;  // the fitted law at Tref
};

// InputError naming the file (and the isotherms) for data that cannot be superposed.
MasterCurve build_master_curve(const DmaData& data, const MasterCurveOptions& opt);

// The compound of a master curve, with its provenance in "source".
Compound compound_from_master(const MasterCurve& m, const std::string& name, const std::string& source, double poisson);

}  // namespace wr
