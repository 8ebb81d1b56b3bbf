#pragma once
// Options of the hysteresis model that `friction` and the sweeps share, applied to the scene in
// one place: the cut-off and the water film.
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "lib/core/errors.hpp"
#include "lib/friction/friction_scene.hpp"

namespace wr::app {

// The cut-off (`friction --q1`, the sweeps' `--friction-q1`): a wavenumber in 1/m, or a named
// criterion: "rms-slope" or "rms-slope:S" (the q1 at which the extrapolated spectrum reaches rms
// slope S, default 1.3; lib/friction/roughness_spectrum.hpp).
inline void apply_q1_option(const std::string& text, const std::string& option, FrictionScene& s) {
  const std::string criterion = "rms-slope";
  if (text.rfind(criterion, 0) == 0) {
    double slope = kDefaultQ1Slope;
    if (text.size() > criterion.size()) {
      if (text[criterion.size()] != ':') throw InputError(option, "\"" + text + "\": write rms-slope or rms-slope:S");
      std::size_t used = 0;
      try {
        slope = std::stod(text.substr(criterion.size() + 1), &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != text.size() - criterion.size() - 1 || !(slope > 0 && slope <= 100))
        throw InputError(option, "\"" + text + "\": the rms slope S of rms-slope:S must be a number in (0, 100]");
    }
    s.q1_rms_slope = slope;
    return;
  }
  std::size_t used = 0;
  double q1 = 0;
  try {
    q1 = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(q1 > 0 && std::isfinite(q1)))
    throw InputError(option, "\"" + text + "\" is neither a wavenumber > 0 in 1/m nor a criterion (rms-slope, rms-slope:S)");
  s.q1 = q1;
}

// The film (--test, --water-film, --no-film): the test's film unless --water-film gives one;
// none with --no-film, which refuses --water-film beside it.
inline void apply_film_options(bool no_film, const CLI::Option& film_opt, double water_film, const std::string& test,
                               FrictionScene& s) {
  if (no_film) {
    if (film_opt.count()) throw InputError("--water-film", "--no-film computes no film: give one or the other");
    return;
  }
  FilmScene film;
  film.test = tyre_test(test);
  if (film_opt.count()) {
    check_water_film(water_film, "--water-film");
    film.test.water_film = water_film;
  }
  s.film = film;
}

}  // namespace wr::app
