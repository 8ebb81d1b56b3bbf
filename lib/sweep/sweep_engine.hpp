#pragma once
// Independent runs of a sweep (coverage, roughness), checkpointed and shared among MPI ranks.
//
// Checkpoint directory: sweep.json (the sweep's parameters, compared on resume) and one
// run-NNNN.json per finished run, each written atomically the moment the run ends, so a killed
// sweep loses at most the runs in progress. Ranks take the next unfinished run from a shared
// counter (MPI one-sided fetch-and-add on rank 0), so slow runs do not leave other ranks idle;
// every run is computed alone on one rank, so results do not depend on the rank count or on
// which rank ran what.
#include <mpi.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

class SweepCheckpoint {
 public:
  explicit SweepCheckpoint(std::string dir) : dir_(std::move(dir)) {}
  const std::string& dir() const { return dir_; }

  // Throws InputError: without `resume`, when the directory exists (an earlier sweep would be
  // mixed in); with it, when the stored parameters differ from `spec`. Call on every rank
  // before start(), so all ranks agree.
  void check(const nlohmann::json& spec, bool resume) const;
  // Creates the directory and writes sweep.json (rank 0).
  void start(const nlohmann::json& spec) const;
  // Finished runs among indices [0, count): index -> record.
  std::map<int, nlohmann::json> finished(int count) const;
  void save(int index, const nlohmann::json& record) const;
  std::string run_path(int index) const;

 private:
  std::string dir_;
};

struct SweepRunDone {
  int index = 0;
  const nlohmann::json* record = nullptr;
  int done_here = 0;          // runs finished by this rank in this invocation
  double seconds_left = 0;    // estimate for the whole sweep (all ranks)
};

// Runs `pending` (run indices) over the ranks of `comm`: run(index) returns the record, which
// is saved with "rank" added; on_done is called after each of this rank's runs. Collective.
// Returns the number of runs (all ranks) whose record has status != "ok".
int run_pending(const SweepCheckpoint& cp, const std::vector<int>& pending, MPI_Comm comm,
                const std::function<nlohmann::json(int)>& run, const std::function<void(const SweepRunDone&)>& on_done);

// "12 s", "3.4 min", "2.1 h" ("?" when not finite).
std::string duration_text(double seconds);

}  // namespace wr
