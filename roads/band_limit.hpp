#pragma once
// A periodic map's Fourier interpolation onto a finer grid with a circular low-pass: the same
// smooth surface, sampled `refine` times more densely, holding only the waves with |q| <= q_max.
// The exact rung of the hysteresis friction (lib/spectral/viscoelastic_sliding.hpp) needs both:
// the band Persson's theory integrates over (a radial one, so the grid's corner waves go), and
// several grid points per shortest wavelength so that the contact spots are resolved.
//
// Exact for a band below the input grid's Nyquist wavenumber: the output, sampled back at the
// input's points, returns the input's band-limited part. The Nyquist row and column of the
// input (a standing wave without direction) are dropped.
#include <cstddef>

#include "lib/core/height_map.hpp"

namespace wr {

// `map` periodic, finite; refine in 1 ... 64; q_max > 0 (1/m). std::invalid_argument otherwise.
HeightMap band_limited(const HeightMap& map, double q_max, std::size_t refine, int threads = 0);

}  // namespace wr
