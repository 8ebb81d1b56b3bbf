#pragma once
// Hertz's frictionless contact of a rigid paraboloid (radius of curvature R) on an elastic
// half-space (Johnson, Contact Mechanics, sec. 4.2), and the fit that reads Hertz's two numbers
// off a computed contact-pressure map. Units: m, N, Pa; E* = E / (1 - nu^2).
#include <cstddef>
#include <span>
#include <vector>

#include "lib/core/height_map.hpp"

namespace wr {

// The obstacle of a Hertz test: an n x n periodic map of the given period (m) holding the cap
// h = -r^2 / (2 R) about the period's centre, apex at h = 0.
HeightMap paraboloid_cap(std::size_t n, double period, double radius);

// Contact radius for a total force F: a = (3 F R / (4 E*))^(1/3).
double hertz_radius(double force, double radius, double e_star);
// Force for a contact radius a: F = 4 E* a^3 / (3 R).
double hertz_force(double contact_radius, double radius, double e_star);

struct HertzFit {
  double radius = 0;        // a, m
  double peak_pressure = 0;  // p0, Pa
  int points = 0;           // nodes used
  bool ok = false;          // false: fewer than 3 usable nodes or a non-decreasing p^2
};

// Hertz's pressure p = p0 sqrt(1 - r^2/a^2) makes p^2 linear in r^2; a least-squares line
// through the nodes with p > 0 and r^2 < inner * a_guess^2 (away from the rim, where the
// lattice cuts the profile) gives a and p0 smoothly, unlike counting contact nodes.
// `pressure`: row-major (ny x nx) nodal pressures on a lattice of spacing h whose node (0, 0)
// sits at (0, 0); (cx, cy) the paraboloid's apex.
HertzFit fit_hertz_pressure(std::span<const double> pressure, int nx, int ny, double h, double cx, double cy,
                            double a_guess, double inner = 0.8);

}  // namespace wr
