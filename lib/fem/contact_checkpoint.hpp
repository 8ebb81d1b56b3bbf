#pragma once
// Checkpoints of a contact test (run_contact_test): after every converged load step the run's
// state is written, and a run started with a restart continues from the last one written, as
// cluster users need under wall-time limits (issue 58). What is kept: the load plan and where
// the run is in it, the converged steps' records, and each rank's block state (displacements,
// contact set, Newton's multipliers and curvature cut) for the last and the one before (the
// secant predictor's). Nothing else carries from one load step to the next (the solvers are
// set up again per step), so a restarted run computes the same curve; with the matrix-free
// multigrid (--solver gmg) to the bit, with the assembled matrix to round-off (its frames are
// rotated incrementally, so its entries depend on the rotations before, ~1e-13).
//
// A restart may change what only shapes the steps to come (RestartableOptions): shear further
// (another --ux or --shear-steps, not with --to-peak: the converged steps are kept and the new
// plan's steps beyond the last one follow), allow other cutbacks (the steps to come get the
// difference), or solve the steps to come to another --tol or --max-penetration.
//
// Files: `path` (an index: format, generation, slot, ranks, fingerprint, the shear's ux and
// steps, the cutbacks, tol, max-penetration), `path.<slot>.shared`
// (plan, records; rank 0) and `path.<slot>.rank<r>` (each rank's state), slot = generation % 2.
// The slot files are written (temporary, then renamed) before the index names them, so a kill at
// any moment leaves the index pointing at a complete checkpoint.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "lib/contact/contact_step.hpp"
#include "lib/core/height_map.hpp"
#include "lib/fem/block_press_shear.hpp"
#include "lib/fem/elastic_block.hpp"

namespace wr {

struct ContactCheckpoint {
  std::uint64_t fingerprint = 0;
  int ranks = 1;
  RestartableOptions options;  // of the run that wrote it
  std::size_t next = 0;  // the index into `plan` of the next load step
  std::vector<LoadTarget> plan;
  LoadTarget last, prev;  // the last converged state and the one before
  int first_shear_iterations = 0;
  std::vector<ContactStep> steps;  // the converged steps so far (rank 0's records)
  BlockState last_state, prev_state;  // this rank's
};

// A 64-bit fingerprint (FNV-1a) of the obstacle's heights and spacing and of every option that
// shapes the run's curve up to its last step: a restart of another scene, another load or another
// solver is refused. Of RestartableOptions only the shear's end counts, and only with to_peak.
std::uint64_t contact_fingerprint(const HeightMap& obstacle, const ContactTestOptions& opt);

// Writes checkpoint `c` (collective on `comm`; every rank passes its own states, rank 0's
// records count). Throws std::runtime_error naming the file when it cannot be written.
void write_contact_checkpoint(const std::string& path, const ContactCheckpoint& c, MPI_Comm comm);

// Reads the checkpoint at `path` (collective). InputError("--restart", ...) when it is missing,
// truncated, of another run (fingerprint) or written by another number of ranks.
ContactCheckpoint read_contact_checkpoint(const std::string& path, std::uint64_t fingerprint, MPI_Comm comm);

}  // namespace wr
