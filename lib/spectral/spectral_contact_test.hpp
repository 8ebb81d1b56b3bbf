#pragma once
// Problem A (normal load, thesis sec. 4.2.2) with the spectral model: the periodic counterpart
// of the FEM block, an elastic layer whose far face is displaced (default thickness: the
// period, a cube's height) or a half-space, pressed onto the rigid periodic obstacle in steps
// of the approach (displacement control, layer only) or of the mean pressure (load control).
// Per step the same record as the FEM (lib/contact/contact_step.hpp): Fz = mean pressure x A0,
// A/A0, sigma* (eq. 5.2), mean separation, worst penetration, iterations, wall time.
#include <functional>
#include <vector>

#include "lib/contact/contact_step.hpp"
#include "lib/core/height_map.hpp"
#include "lib/spectral/normal_contact.hpp"

namespace wr {

struct SpectralTestOptions {
  double uz = 0;        // m, final approach of the far face (layer); or
  double pressure = 0;  // Pa, final mean pressure (load control); exactly one of the two > 0
  int steps = 4;
  ElasticBody body;     // thickness: m, inf for the half-space
  SpectralOptions solver;
  bool face_maps = false;
  double rms_slope = 0;  // of the obstacle (normalises sigma*); > 0
};

struct SpectralTestResult {
  std::size_t nx = 0, ny = 0;  // grid points (the obstacle's samples)
  double spacing = 0;          // m
  std::vector<ContactStep> steps;
  bool failed = false;
  double wall_setup = 0, wall_s = 0;  // s
};

// Throws InputError naming the option at fault.
void check_spectral_test_options(const SpectralTestOptions& opt);

// Throws InputError for bad options. A step that does not converge ends the run (failed).
SpectralTestResult run_spectral_normal_test(const HeightMap& obstacle, const SpectralTestOptions& opt,
                                            const std::function<void(const ContactStep&)>& on_step = {});

}  // namespace wr
