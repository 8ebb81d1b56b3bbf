#include "lib/sweep/sweep_engine.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "lib/core/content_hash.hpp"
#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/staging.hpp"
#include "roads/synthesize.hpp"
#include "wetroad/version.hpp"

namespace wr {
namespace {

constexpr const char* kKeyField = "sweep_key";
constexpr const char* kChecksumField = "checksum";

enum class Read { absent, corrupt, ok };

Read read_json(const std::string& path, nlohmann::json* out) {
  std::ifstream in(path);
  if (!in) return Read::absent;
  try {
    *out = nlohmann::json::parse(in);
    return Read::ok;
  } catch (const nlohmann::json::exception&) {
    return Read::corrupt;
  }
}

std::string short_value(const nlohmann::json& v) {
  std::string s = v.dump();
  return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

// The first difference between the checkpointed spec and this one, in words: which option (a
// JSON path such as scene.uz) or which file changed.
std::string first_difference(const nlohmann::json& stored, const nlohmann::json& spec) {
  const nlohmann::json patch = nlohmann::json::diff(stored, spec);
  if (patch.empty()) return "";
  const std::string path = patch[0]["path"].get<std::string>();
  if (path == "/surface/content_sha256")
    return "the surface file " + spec["surface"].value("path", std::string("?")) +
           " has other content than when the sweep was checkpointed";
  // A change inside a list (an element added: ".../-", or changed: ".../3") is told as the whole
  // list, which is what the user typed (--coverages 0 0.2 0.4).
  nlohmann::json::json_pointer ptr(path);
  while (!ptr.empty()) {
    const nlohmann::json::json_pointer parent = ptr.parent_pointer();
    const bool in_list = (stored.contains(parent) && stored[parent].is_array()) || (spec.contains(parent) && spec[parent].is_array());
    if (!in_list) break;
    ptr = parent;
  }
  std::string name = ptr.to_string().substr(1);
  std::replace(name.begin(), name.end(), '/', '.');
  const std::string was = stored.contains(ptr) ? short_value(stored[ptr]) : "absent";
  const std::string now = spec.contains(ptr) ? short_value(spec[ptr]) : "absent";
  return name + " is " + now + ", was " + was;
}

// The checksum of a record: SHA-256 of its JSON without the checksum itself.
std::string record_checksum(nlohmann::json record) {
  record.erase(kChecksumField);
  return sha256_hex(record.dump());
}

}  // namespace

std::string sweep_key(const nlohmann::json& spec) { return sha256_hex(spec.dump() + "\n" + kVersion); }

nlohmann::json with_surface_digest(nlohmann::json spec) {
  if (spec.contains("surface") && spec["surface"].contains("path"))
    spec["surface"]["content_sha256"] = sha256_file_hex(spec["surface"]["path"].get<std::string>());
  return spec;
}

SweepCheckpoint::~SweepCheckpoint() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
}

std::string SweepCheckpoint::run_path(int index) const {
  char name[32];
  std::snprintf(name, sizeof name, "/run-%04d.json", index);
  return dir_ + name;
}

void SweepCheckpoint::check(const nlohmann::json& spec, bool resume) const {
  const bool exists = std::filesystem::exists(dir_);
  if (!resume) {
    if (exists) throw InputError(dir_, "a checkpoint of an earlier sweep exists: continue it with --resume, or remove it");
    return;
  }
  if (!exists) return;  // nothing to resume: a fresh start
  const std::string sweep_json = dir_ + "/sweep.json";
  nlohmann::json stored;
  const Read r = read_json(sweep_json, &stored);
  if (r != Read::ok || !stored.is_object() || !stored.contains("spec"))
    throw InputError(sweep_json, std::string(r == Read::absent ? "missing" : "corrupt") +
                                     ": the checkpointed runs cannot be matched to this sweep; remove " + dir_ +
                                     " to start again");
  if (stored.value("version", std::string()) != kVersion)
    throw InputError(sweep_json, "--resume of a sweep made by wetroad " + stored.value("version", std::string("?")) +
                                     ", this is " + kVersion + ": runs of two versions would be mixed; remove " +
                                     dir_ + " to start again");
  if (stored["spec"] != spec)
    throw InputError(sweep_json, "--resume with different sweep parameters than the checkpointed sweep: " +
                                     first_difference(stored["spec"], spec));
}

void SweepCheckpoint::start(const nlohmann::json& spec, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  key_ = sweep_key(spec);
  std::string error;
  if (rank == 0) {
    try {
      std::error_code ec;
      std::filesystem::create_directories(dir_, ec);
      if (ec) throw InputError(dir_, "cannot create the checkpoint directory: " + ec.message());
      const std::string lock = dir_ + "/lock";
      lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
      if (lock_fd_ < 0) throw InputError(lock, std::string("cannot open: ") + std::strerror(errno));
      // flock: released by the kernel when the process ends, however it ends (no stale lock).
      if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0)
        throw InputError(dir_, "another wetroad process is running this sweep (its checkpoint is locked); wait for "
                               "it, or stop it and --resume");
      remove_stale_staging_in(dir_);  // records of an earlier process killed mid-write
      write_text_atomically(dir_ + "/sweep.json",
                            nlohmann::json({{"spec", spec}, {"version", kVersion}, {"key", key_}}).dump(2) + "\n");
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  int length = int(error.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  error.resize(std::size_t(length));
  if (length > 0) MPI_Bcast(error.data(), length, MPI_CHAR, 0, comm);
  if (!error.empty()) throw InputError("", error);
}

std::map<int, nlohmann::json> SweepCheckpoint::finished(int count) const {
  std::map<int, nlohmann::json> done;
  for (int i = 0; i < count; ++i) {
    nlohmann::json r;
    const std::string path = run_path(i);
    const Read got = read_json(path, &r);
    if (got == Read::absent) continue;
    // Writes are atomic: a record that does not parse, belongs to another sweep or was edited
    // did not come from this sweep's runs. Refuse rather than mix or silently redo it.
    if (got == Read::corrupt || !r.is_object() || r.value("index", -1) != i)
      throw InputError(path, "not a run record of this sweep (corrupt); remove it to recompute the run");
    if (r.value(kKeyField, std::string()) != key_)
      throw InputError(path, "a run of another sweep (its key differs from sweep.json's); remove it to recompute the run");
    if (r.value(kChecksumField, std::string()) != record_checksum(r))
      throw InputError(path, "its checksum does not match its content (edited or corrupt); remove it to recompute the run");
    done[i] = std::move(r);
  }
  return done;
}

void SweepCheckpoint::save(int index, nlohmann::json record) const {
  record[kKeyField] = key_;
  record[kChecksumField] = record_checksum(record);
  write_text_atomically(run_path(index), record.dump(1) + "\n");
}

int run_pending(const SweepCheckpoint& cp, const std::vector<int>& pending, MPI_Comm comm,
                const std::function<nlohmann::json(int)>& run, const std::function<void(const SweepRunDone&)>& on_done) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // The shared counter of claimed runs lives on rank 0; passive-target fetch-and-add needs no
  // cooperation from rank 0 while it computes.
  int* counter = nullptr;
  MPI_Win win;
  MPI_Win_allocate(rank == 0 ? sizeof(int) : 0, sizeof(int), MPI_INFO_NULL, comm, &counter, &win);
  if (rank == 0) *counter = 0;
  MPI_Barrier(comm);
  const auto t0 = std::chrono::steady_clock::now();
  const int one = 1;
  int failures = 0, done_here = 0;
  for (;;) {
    int slot = 0;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, win);
    MPI_Fetch_and_op(&one, &slot, MPI_INT, 0, 0, MPI_SUM, win);
    MPI_Win_unlock(0, win);
    if (slot >= int(pending.size())) break;
    const int index = pending[std::size_t(slot)];
    nlohmann::json rec = run(index);
    rec["rank"] = rank;
    cp.save(index, rec);
    ++done_here;
    if (rec.value("status", "") != "ok") ++failures;
    if (on_done) {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      // This rank's pace times the runs not yet claimed, shared by all ranks, plus what the
      // other ranks are still doing (about one run each).
      const double per_run = el / done_here;
      const double left = per_run * (double(pending.size()) - double(slot + 1)) / ranks;
      on_done({index, &rec, done_here, left});
    }
  }
  MPI_Win_free(&win);
  int all = 0;
  MPI_Allreduce(&failures, &all, 1, MPI_INT, MPI_SUM, comm);
  return all;
}

std::string duration_text(double seconds) {
  char b[32];
  if (!std::isfinite(seconds)) return "?";
  if (seconds < 120) std::snprintf(b, sizeof b, "%.0f s", seconds);
  else if (seconds < 7200) std::snprintf(b, sizeof b, "%.1f min", seconds / 60);
  else std::snprintf(b, sizeof b, "%.1f h", seconds / 3600);
  return b;
}

void check_realizations(int realizations, std::uint64_t first_seed) {
  if (realizations < 1 || realizations > 100000) throw InputError("--realizations", "must be 1 ... 100000");
  if (first_seed > kMaxSeed || kMaxSeed - first_seed < std::uint64_t(realizations - 1))
    throw InputError("--seed", "the realizations' seeds (seed ... seed + R - 1) must stay within 0 ... " +
                                   std::to_string(kMaxSeed));
}

}  // namespace wr
