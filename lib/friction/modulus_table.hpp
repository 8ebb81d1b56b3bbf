#pragma once
// A measured master curve given as a table (omega, E', E'') at Tref, turned into the Prony series
// the friction model uses, and checked for causality on the way.
//
// Causality: E' and E'' of a linear, causal, relaxing material are not independent: they are
// Kramers-Kronig transforms of each other (E'(w) - E'(0) is fixed by E'' at all frequencies).
// Every Prony series with dE_i >= 0 satisfies the relations exactly, and a dense one (here
// kTermsPerDecade relaxation times per decade, spanning the table's range and one decade beyond
// each end) represents any smooth causal master curve to well under a percent. So the table is
// fitted, E' and E'' together, by non-negative least squares on relative residuals, and a misfit
// above kCausalityTolerance means no causal material has this pair of curves: the table is
// refused, naming the frequency where the two curves disagree most. (The discrete KK test of
// Booij & Thoone, Rheol. Acta 21, 15 (1982), in the form of a constrained fit.)
#include <cstddef>
#include <string>
#include <vector>

#include "lib/friction/compound.hpp"

namespace wr {

constexpr int kTermsPerDecade = 3;
constexpr double kCausalityTolerance = 0.10;  // largest relative misfit of E' or E'' accepted
// Bounds on what a table may cost before it is fitted (the fit is a dense NNLS of 2 rows per
// frequency by 3 columns per decade): measured master curves have tens to hundreds of rows over
// 10 to 25 decades of reduced frequency. Frequencies outside [kMinOmega, kMaxOmega] rad/s would
// put relaxation times beyond the doubles (1 / 5e-324 is inf).
constexpr std::size_t kMaxTableRows = 2000;
constexpr double kMaxTableDecades = 40;
constexpr double kMinOmega = 1e-30, kMaxOmega = 1e30;

struct ModulusTable {
  std::vector<double> omega;    // rad/s, ascending, > 0
  std::vector<double> storage;  // E', Pa, > 0
  std::vector<double> loss;     // E'', Pa, > 0
};

struct PronyFit {
  double e_relaxed = 0;
  std::vector<PronyTerm> terms;  // terms with dE = 0 dropped
  double max_misfit = 0;         // largest |model / table - 1| over E' and E''
  double rms_misfit = 0;
  double worst_omega = 0;        // rad/s, where the largest misfit is
  bool worst_is_loss = false;
};

// Throws InputError(source, ...) for a malformed table (fewer than 4 or more than kMaxTableRows
// rows, unsorted frequencies or ones outside [kMinOmega, kMaxOmega], more than kMaxTableDecades
// decades, non-positive or non-finite moduli, columns of different lengths).
void check_modulus_table(const ModulusTable& t, const std::string& source);
PronyFit fit_prony(const ModulusTable& t);
// fit_prony, then InputError(source, "not causal: ...") when max_misfit > kCausalityTolerance.
PronyFit causal_prony_fit(const ModulusTable& t, const std::string& source);

}  // namespace wr
