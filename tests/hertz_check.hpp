#pragma once
// The Hertz check shared by the FEM's paraboloid tests: contact radius, force and peak pressure
// fitted from the face's pressure map (lib/analytic/hertz.hpp) against Hertz's, each within
// `tolerance` (relative). The face maps live on rank 0; other ranks check nothing.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>

#include "lib/analytic/hertz.hpp"
#include "lib/fem/elastic_block.hpp"

namespace wr {

// s: a solve with face maps on an (n + 1)^2 face of side L, the paraboloid of radius R at the
// face's centre, E = 1 and Poisson's ratio nu.
inline void expect_hertz_contact(const ContactSolution& s, double L, int n, double R, double nu, double tolerance) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  const double e_star = 1.0 / (1 - nu * nu), h = L / n;
  const double a_count = std::sqrt(double(s.contact_nodes) * h * h / M_PI);
  const HertzFit fit = fit_hertz_pressure(s.face_pressure, n + 1, n + 1, h, L / 2, L / 2, a_count);
  ASSERT_TRUE(fit.ok);
  const double a_hertz = hertz_radius(s.fz, R, e_star);
  EXPECT_NEAR(fit.radius / a_hertz, 1.0, tolerance);
  EXPECT_NEAR(s.fz / hertz_force(fit.radius, R, e_star), 1.0, tolerance);
  EXPECT_NEAR(fit.peak_pressure / (3 * s.fz / (2 * M_PI * a_hertz * a_hertz)), 1.0, tolerance);
}

}  // namespace wr
