#pragma once
// The coverage sweep (thesis sec. 5.4.2, Figures 5.25-5.26): friction of an elastic block on one
// surface (or R synthetic realizations) wetted to a list of water coverages.
//
// Each run: surface (file, or synthesis with seed + realization) -> water at the target coverage
// -> the wet surface max(h, level) as the rigid obstacle (sealed pools act as a solid, thesis
// assumption A3) -> contact scene (Problem A then B) -> one JSON record. Coverage 0 is the dry
// surface. Targets up to the surface's drained limit (water running off through the periodic
// surface, exact torus drainage) are drained fills; beyond it the water stands (stagnant fill,
// the thesis's periodic boundary conditions). A target the surface cannot reach in either mode
// fails that run with the reason, as does a contact run that does not converge.
//
// Runs are independent: they are spread over MPI ranks (each FEM block on PETSC_COMM_SELF), and
// every finished run is written at once, atomically, to the checkpoint directory
// (`<out>.runs/run-NNNN.json`): a killed sweep resumes without redoing them, and the results
// do not depend on the rank count (each run is computed alone, with deterministic FFT plans).
//
// Run record (SI units; JSON): index, realization, seed, ground_mpd (the dry surface's MPD, with
// ground_mpd_note when the baseline or filter departs from ISO 13473-1), target, water ("dry" | "drained" |
// "stagnant"), coverage, rain_depth, drained_limit, mean_pool_depth, max_pool_depth,
// stored_volume, lakes, wet_sq, wet_rms_slope, psd {q, C}, contact {model, mu_peak, ux_peak,
// area_at_peak, area_normal, fz_normal, failed, message, unknowns, steps [...], validity},
// status ("ok" | "failed"), message, wall {surface, water, contact, total}, rank.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/scene/contact_scene.hpp"
#include "lib/friction/friction_scene.hpp"
#include "roads/synthesize.hpp"
#include "water/rain_fill.hpp"

namespace wr {

struct CoverageSweepSpec {
  std::vector<double> coverages;     // targets in [0, 1), ascending; 0 = dry
  int realizations = 1;              // synthetic surfaces only
  std::optional<SynthParams> synth;  // synthetic surfaces (seed + r for realization r) ...
  std::string surface_path;          // ... or one surface file
  ContactScene scene;                     // the contact models (fem, spectral) ...
  std::optional<FrictionScene> hysteresis;  // ... or the hysteresis model at its one speed
  Tiling tiling = Tiling::torus;
  int connectivity = 4;
};

struct CoverageRunKey {
  int index = 0, realization = 0;
  double target = 0;
};

// Throws InputError naming the option at fault (coverages, realizations, scene).
void check_sweep_spec(const CoverageSweepSpec& s);

// Realization-major: all coverages of realization 0, then of 1, ...
std::vector<CoverageRunKey> plan_runs(const CoverageSweepSpec& s);

// The spec as stored with the results and compared on --resume.
nlohmann::json sweep_spec_json(const CoverageSweepSpec& s);

// Computes runs; keeps the last realization's surface and drained limit between calls.
class CoverageRunner {
 public:
  CoverageRunner(const CoverageSweepSpec& spec, MPI_Comm contact_comm, int threads);
  // Never throws: an exception becomes a failed record with the key and the reason. `on_step`
  // (may be empty) hears of every load step of the contact run as it ends, for progress lines.
  nlohmann::json run(const CoverageRunKey& key, const StepListener& on_step = {});

 private:
  nlohmann::json run_unguarded(const CoverageRunKey& key, const StepListener& on_step);
  void load_realization(int r);
  CoverageSweepSpec spec_;
  MPI_Comm comm_;
  int threads_;
  int loaded_ = -1;
  HeightMap ground_;
  std::uint64_t seed_ = 0;
  double drained_limit_ = 0, wall_surface_ = 0;
  double ground_mpd_ = 0;  // m, ISO 13473-1 over the map's rows and columns
  std::string ground_mpd_note_;
};

// One row per target coverage: sample_statistics (lib/sweep/sample_statistics.hpp) of mu_peak,
// mu_ratio (mu / the same realization's dry mu), area at the peak and after the normal load,
// achieved coverage, mean pool depth and wet rms height (with the hysteresis model also
// mu_ratio_homogeneous, the homogeneous sealing model's ratio; mu_ratio is the local model's); n counts the runs that finished. mu_ratio leaves out realizations whose dry mu is not positive
// (its n says how many remain). Runs are records as above, in any order.
nlohmann::json coverage_table(const std::vector<nlohmann::json>& runs);

}  // namespace wr
