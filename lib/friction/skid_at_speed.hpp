#pragma once
// Wet friction at speed: rubber sliding on a road under a water film, each road element under
// the tread for the time Lc / v while the film drains through the texture (Moore's three zones;
// Lorenz & Persson, Eur. Phys. J. E 32, 281 (2010)), and the skid numbers, speed constant and
// hydroplaning speed that follow. The hysteresis model's rung "squeeze-out of a water film at
// speed" (design.md).
//
// At sliding speed v (a locked wheel: the tread slides at the vehicle's speed):
//  1. the interface: Persson's load-separation p_c(u), A(u) of the rubber excited at q v
//     (lib/friction/load_separation.hpp) and the effective-medium flow conductance K(u, A)
//     (lib/flow/effective_medium.hpp) with the rms height of the same spectrum;
//  2. the squeeze-out u(t) from the film (u0 = the film's volume per area; when the texture's
//     voids at equilibrium hold it all, the tread lands on the asperities at once) through the
//     rib's drainage length (lib/friction/squeeze_out.hpp), water at the road's temperature;
//  3. the friction averaged over the patch, t in [0, Lc / v]:
//       mu(v) = mu_h(v) <p_c / sigma0> + eta v <(1 - A) / u> / sigma0,
//     the asperities' share of the load slides with the hysteresis friction mu_h(v) of the
//     hysteresis model (Persson's mu at sigma0 with sealing: it varies weakly with the load), and
//     the water-borne share excites no dissipation (the sealed film is flat) but is sheared as
//     a Couette film of thickness u over the free area.
// From mu(v) at 20 ... 100 km/h: SN(v) = 100 mu, the test's skid number at its slip speed, the
// speed constant Sp of ASTM E1960 (mu(S) = mu(S0) exp((S0 - S)/Sp), fitted to ln mu over the
// range by least squares), FR60 = mu at 60 km/h, and the hydroplaning speed: the speed at which
// the asperities carry less than 1 % of the load anywhere in the patch (Lc / v equals the time
// the film needs to drain to the first asperity contact).
// Units: SI inside; Sp and speeds in km/h where named so.
#include <functional>
#include <limits>
#include <vector>

#include "lib/friction/compound.hpp"
#include "lib/friction/hysteresis_friction.hpp"
#include "lib/friction/roughness_spectrum.hpp"
#include "lib/friction/squeeze_out.hpp"
#include "lib/friction/tyre_test.hpp"

namespace wr {

// The effective medium's conductance stays within a factor 1.6 of the map's up to this contact
// fraction and drifts to 2.7 and beyond near the percolation threshold (docs/validation.md,
// "The mean-field rung against the map"): above it the drain times need the map's flow.
constexpr double kMeanFieldFlowMaxContact = 0.3;

struct FilmScene {
  TyreTest test;              // patch, drainage length, slip speed; test.water_film is the film
  double critical_contact = 0.42;  // the effective medium's percolation threshold
};

struct FilmPoint {
  double v = 0;               // m/s
  double mu = 0;              // wet friction at speed (hysteresis share + viscous film)
  double mu_hysteresis = 0;   // mu_h(v) of the drained road
  double mu_viscous = 0;      // the film's shear
  double load_share = 0;      // <p_c / sigma0> over the patch
  double patch_time = 0;      // s, Lc / v
  double drain_time = 0;      // s, until the asperities carry 90 % of the load (inf: never)
  double contact_time = 0;    // s, until they carry 1 % (the first contact)
  double equilibrium_separation = 0;  // m, u at sigma0
  double equilibrium_contact = 0;     // A/A0 at sigma0 (Persson's, at q1)
  double final_separation = 0;        // m, u when the element leaves the patch
  bool trapped = false;       // the water stopped draining (the free area no longer percolates)
};

struct SkidCurve {
  std::vector<FilmPoint> points;      // at the scene's speeds
  std::vector<FilmPoint> skid;        // 20, 25, ..., 100 km/h
  FilmPoint at_test;                  // at the test's slip speed
  double sn = 0;                      // 100 mu at the test's slip speed
  double sp_kmh = 0;                  // inf when mu does not fall with speed
  double sp_fit_rms = 0;              // rms of the ln mu residuals of the exponential fit
  double fr60 = 0;                    // mu at 60 km/h
  double hydroplaning_kmh = std::numeric_limits<double>::infinity();
  std::vector<SqueezeState> squeeze_at_test;  // u(t) at the test's slip speed, <= 200 nodes
};

// The squeeze-out and patch average at one speed, with mu_h the hysteresis friction there.
FilmPoint film_friction(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                        const FilmScene& film, double v, double mu_h);

// The squeeze-out history of the film at speed v (m/s).
SqueezeHistory film_squeeze(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                            const FilmScene& film, double v);

// The whole curve: mu_h from `hysteresis` (v -> mu_h(v), e.g. the hysteresis model on the dry
// or the sealed wet spectrum), evaluated at the scene's speeds and the skid speeds, in parallel
// over speeds (opt.threads).
SkidCurve skid_curve(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                     const FilmScene& film, const std::vector<double>& speeds,
                     const std::function<std::vector<double>(const std::vector<double>&)>& hysteresis);

// ASTM E1960's speed constant fitted to (speed km/h, mu) pairs by least squares in ln mu: Sp
// (km/h; +inf when the fitted slope is >= 0) and the fit's rms residual. Needs >= 2 points, mu > 0.
std::pair<double, double> fit_speed_constant(const std::vector<double>& speeds_kmh, const std::vector<double>& mu);

// The hydroplaning speed (km/h) of a film on this road: the fixed point v = Lc / t_1%(v).
double hydroplaning_speed(const RoughnessSpectrum& psd, const Compound& compound, const FrictionOptions& opt,
                          const FilmScene& film);

}  // namespace wr
