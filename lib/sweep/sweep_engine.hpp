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

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

// Every run is keyed to the sweep: `spec` holds everything that determines the runs (all
// options, the surface file's SHA-256, see with_surface_digest), and the key is the SHA-256 of
// spec and version. Each run record carries the key and a checksum of its own content, so a
// resume cannot mix runs of two inputs, two option sets, two versions, or an edited record.
class SweepCheckpoint {
 public:
  explicit SweepCheckpoint(std::string dir) : dir_(std::move(dir)) {}
  ~SweepCheckpoint();
  SweepCheckpoint(const SweepCheckpoint&) = delete;
  SweepCheckpoint& operator=(const SweepCheckpoint&) = delete;
  const std::string& dir() const { return dir_; }

  // Throws InputError: without `resume`, when the directory exists (an earlier sweep would be
  // mixed in); with it, when sweep.json is missing or corrupt while the directory exists, or
  // when the stored key differs (the message names the first option or file that changed, or
  // the version). Call on every rank before start(), so all ranks agree.
  void check(const nlohmann::json& spec, bool resume) const;
  // Collective over `comm`: rank 0 takes the checkpoint's lock (held until this object dies),
  // creates the directory and writes sweep.json. Every rank throws InputError when the lock is
  // held by another process (two processes on one sweep: one runs, the other refuses).
  void start(const nlohmann::json& spec, MPI_Comm comm);
  // Finished runs among indices [0, count): index -> record. Throws InputError naming a run
  // file whose key is another sweep's or whose checksum does not match its content.
  std::map<int, nlohmann::json> finished(int count) const;
  // Writes the record with the sweep's key and its checksum (after start()).
  void save(int index, nlohmann::json record) const;
  std::string run_path(int index) const;

 private:
  std::string dir_;
  std::string key_;   // set by start()
  int lock_fd_ = -1;  // rank 0, while running
};

// The SHA-256 key of a sweep: its spec and this build's version.
std::string sweep_key(const nlohmann::json& spec);
// `spec` with the content of the surface file it names (spec["surface"]["path"]) added as
// spec["surface"]["content_sha256"]; unchanged for synthetic surfaces.
nlohmann::json with_surface_digest(nlohmann::json spec);

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

// --realizations R (1 ... 100000) of synthetic surfaces seeded seed, seed + 1, ...: the last
// seed must stay within kMaxSeed (roads/synthesize.hpp). InputError naming the option otherwise.
void check_realizations(int realizations, std::uint64_t first_seed);

}  // namespace wr
