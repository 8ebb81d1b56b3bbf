#pragma once
// `wetroad bench friction`: speed and accuracy of the hysteresis model.
// On an N x N default-like surface (the default scene's 30 mm tile, h0 0.3 mm, H 0.7, q0 = 5 qL,
// dx = 30 mm / N, spectrum to the grid's Nyquist wavenumber): the time of the
// spectrum (FFT, radial PSD, fit), of mu at S speeds isothermal and with the flash temperature
// (best of `repeats`), and mu's error against a 400-points-per-decade reference for a ladder of
// quadrature densities (speed against accuracy).
#include <cstddef>

#include <nlohmann/json.hpp>

namespace wr::bench {

nlohmann::json friction_speed(std::size_t n, int speeds, int repeats, int threads);

}  // namespace wr::bench
