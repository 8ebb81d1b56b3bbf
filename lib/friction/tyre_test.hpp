#pragma once
// What a skid test contributes to wet friction at speed: the tyre's contact patch, the path the
// water takes out of it, the water film and the slip speed. Two built-in tests (ASTM E274's
// locked-wheel trailer with each of its standard tyres) and a JSON file for any other.
//
// Built-in values (docs/friction-model.md, "Wet friction at speed", gives each one's source):
//  - E274 (ASTM E274/E274M): slip speed 64 km/h (the wheel locked: the tread slides at the
//    vehicle's speed), a nominal 0.5 mm water film sprayed ahead of the wheel, test load 4.8 kN
//    (1085 lbf) on a tyre inflated to 165 kPa (24 psi): a patch of about 0.029 m^2, about
//    0.15 m wide (the G78-15 tyre's tread) and so ~0.19 m long; patch_length = 0.19 m;
//  - e274-ribbed: ASTM E501's standard rib tyre: seven ribs between circumferential grooves
//    across the 0.15 m tread; the water squeezed from under a rib escapes sideways into the
//    grooves: drainage_length = the rib's width, about 0.018 m;
//  - e274-smooth: ASTM E524's standard smooth tyre: no grooves; the water escapes across the
//    whole tread width, drainage_length = 0.15 m; this tyre is the one sensitive to the road's
//    macrotexture, as E524 is specified to be.
// File format (JSON, SI units; all keys but "source" and "water_film_m" required):
//   {"name": "...", "source": "...", "patch_length_m": 0.19, "drainage_length_m": 0.018,
//    "slip_speed_m_s": 17.9, "water_film_m": 0.5e-3}
#include <string>

namespace wr {

struct TyreTest {
  std::string name, source;
  double patch_length = 0.19;      // m, Lc: a road element spends Lc / v under the sliding tread
  double drainage_length = 0.018;  // m, L of the squeeze-out (lib/friction/squeeze_out.hpp)
  double slip_speed = 17.9;        // m/s, where the test's skid number is read
  double water_film = 0.5e-3;      // m, the film's volume per unit area ahead of the tyre
};

// Bounds a test must keep (InputError outside them).
constexpr double kMaxWaterFilm = 10e-3;  // m: deeper water than a tread groove is dynamic
                                         // hydroplaning's regime, which the model does not have

// "e274-ribbed", "e274-smooth", or a JSON file's path (InputError naming the file and key).
TyreTest tyre_test(const std::string& name_or_file);
// InputError naming `option` for a film outside (0, kMaxWaterFilm] or not finite.
void check_water_film(double film, const std::string& option);

// Dynamic viscosity of liquid water (Pa s) at `celsius` in 0 ... 100 deg C (Vogel's equation,
// eta = 2.414e-5 * 10^(247.8 / (T - 140)), T in K; 1.0e-3 Pa s at 20 deg C, within 2.5 % of
// the IAPWS values over 0-100 deg C). Outside: clamped to the range's ends.
double water_viscosity(double celsius);

}  // namespace wr
