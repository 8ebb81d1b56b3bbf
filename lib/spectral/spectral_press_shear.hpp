#pragma once
// The thesis's contact experiments (sec. 4.2.2) with the spectral model: the periodic
// counterpart of the FEM block, an elastic layer whose far face is displaced (default
// thickness: the period, a cube's height) or a half-space.
//
// Problem A alone (`shear` false): the classic small-slope normal contact, pressed in steps of
// the approach (displacement control, layer) or of the mean pressure (load control).
//
// Problem B (`shear` true, layer and displacement control only): the far face is moved by
// (ux, 0, -uz) in steps, first down, then sideways. The local contact stays frictionless: the
// obstacle pushes along its normal, so each contact point carries the vertical traction p and
// the tangential traction -p grad h (grad h at the point the face now sits over). Tangential
// tractions displace the face sideways and, through the (1 - 2 nu) coupling, vertically
// (traction_response.hpp); the face then sits over other parts of the obstacle. Each step
// iterates, like the thesis's Algorithm 1: sample the obstacle (height, slope) under the
// displaced face points -> normal solve with the coupling's vertical displacement folded into
// the obstacle -> tangential displacements of the new tractions -> damped update, until the
// relative change of the face displacement is below `geometry_tolerance`.
// mu = Fx / Fz with Fx = sum p dh/dx dA: the force that holds the far face in place.
//
// Per step the same record as the FEM (lib/contact/contact_step.hpp).
#include <functional>
#include <vector>

#include "lib/contact/contact_step.hpp"
#include "lib/core/height_map.hpp"
#include "lib/spectral/normal_contact.hpp"

namespace wr {

struct SpectralTestOptions {
  double uz = 0;        // m, final approach of the far face (layer); or
  double pressure = 0;  // Pa, final mean pressure (load control); exactly one of the two > 0
  int steps = 4;        // normal steps
  bool shear = false;   // Problem B after A
  double ux = 0;        // m, final tangential displacement of the far face
  int shear_steps = 4;
  double damping = 0.8;              // of the geometry iteration (alpha_c)
  double geometry_tolerance = 1e-6;  // relative change of the face displacement
  int max_geometry_iterations = 200;
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

// A step that does not converge ends the run (failed); the finished steps are kept.
SpectralTestResult run_spectral_contact_test(const HeightMap& obstacle, const SpectralTestOptions& opt,
                                             const StepListener& on_step = {});

}  // namespace wr
