#pragma once
// How far a predicted skid number moves when the inputs a user knows only within ranges move:
// the nominal pressure, the temperature, the water film, the cut-off q1 and (for a synthetic
// compound) the position of its master curve in frequency. Issue 56, part 3.
//
// Method (defensible and cheap: each evaluation is the skid number at the test's speed alone,
// the hysteresis friction at one speed and the film's squeeze-out there, about 1/100 of a full
// run; the spectra are reused, q1 moves along the fitted extension):
//  - one-at-a-time: each input at the low and the high end of its range, the others nominal:
//    the tornado chart, inputs ordered by the swing they cause;
//  - a Latin hypercube over all inputs together (n samples, one per stratum of every input,
//    strata paired at random; uniform in each range, logarithmic for q1 and the film): the band
//    between the 5th and the 95th percentile, and the extremes. For a response monotone in each
//    input the extremes of any sample lie inside the box's corners' (tested).
// Default ranges (documented in docs/friction-model.md, options of `friction`): sigma0 x 2/3 ...
// x 4/3; T0 -10 ... +10 K; film x 1/2 ... x 2; q1 x 1/3 ... x 3; master curve shifted -0.5 ...
// +0.5 decades in frequency (a synthetic compound only).
#include <cstdint>
#include <string>
#include <vector>

#include "lib/friction/compound.hpp"
#include "lib/friction/hysteresis_friction.hpp"
#include "lib/friction/roughness_spectrum.hpp"
#include "lib/friction/skid_at_speed.hpp"

namespace wr {

struct InputRange {
  std::string name;          // "pressure", "temperature", "water_film", "q1", "compound_shift"
  double low = 0, high = 0;  // in the input's own unit: Pa, deg C, m, 1/m, decades
  bool logarithmic = false;
};

struct UncertaintySetup {
  std::vector<InputRange> ranges;
  int samples = 32;          // Latin-hypercube size
  std::uint64_t seed = 1;
};

struct TornadoRow {
  std::string name;
  double low = 0, high = 0;         // the input's range
  double sn_low = 0, sn_high = 0;   // SN with the input at each end
};

struct SkidBand {
  double nominal = 0, p05 = 0, p95 = 0, min = 0, max = 0;
  std::vector<TornadoRow> tornado;  // by swing, largest first
  std::vector<double> samples;      // SN of each Latin-hypercube sample
  int evaluations = 0;
};

// What an evaluation needs: the spectra of the run (the dry one, which the squeeze-out uses, and
// the one the hysteresis friction slides on: dry, or the sealed wet one with its area scale).
struct SkidInputs {
  RoughnessSpectrum dry, hysteresis;
  double hysteresis_scale = 1;
  Compound compound;
  FrictionOptions options;
  FilmScene film;
};

// The default ranges around the nominal inputs (compound_shift only for a synthetic compound).
std::vector<InputRange> default_ranges(const SkidInputs& in);

// SN = 100 mu at the test's slip speed with the named inputs set (names as InputRange).
double skid_number_at(const SkidInputs& in, const std::vector<std::pair<std::string, double>>& values);

SkidBand skid_number_band(const SkidInputs& in, const UncertaintySetup& setup);

}  // namespace wr
