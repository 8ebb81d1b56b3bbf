#pragma once
// The gap fields the thin-film flow (thin_film_flow.hpp) runs on: that of an elastic contact
// solution, and that of a rigid flat cutting the surface (the bearing-area picture).
#include <vector>

#include "lib/core/big_buffer.hpp"
#include "lib/core/height_map.hpp"

namespace wr {

// The gap of a contact solution on `like`'s grid (m): 0 where the contact pressure is > 0 (the
// solver's gap there is round-off of either sign), max(g, 0) elsewhere (a penetration left
// within the solver's tolerance counts as closed). `pressure` and `gap` row-major, like.size()
// values each; std::invalid_argument otherwise.
HeightMap contact_gap_map(const HeightMap& like, const BigVector& pressure, const BigVector& gap);

// A rigid flat at height `level` (m) over `surface` (heights m): gap max(level - h, 0), periodic
// as the surface.
HeightMap rigid_flat_gap(const HeightMap& surface, double level);

// The flat's level at which exactly round(fraction * N) points are in contact (h >= level: the
// highest ones); fraction in (0, 1), else InputError("--contact-fraction", ...).
double level_at_contact_fraction(const HeightMap& surface, double fraction);

// The flat's level at which the mean gap over all points is `separation` (m, > 0; else
// InputError("--separation", ...)); above the highest point when the separation exceeds
// max h - mean h (no contact then). Bisection to 1e-12 of the surface's height range.
double level_at_mean_separation(const HeightMap& surface, double separation);

// Fraction of points with gap == 0 (in contact).
double contact_fraction(const HeightMap& gap);

}  // namespace wr
