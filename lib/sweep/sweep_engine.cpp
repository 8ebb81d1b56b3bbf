#include "lib/sweep/sweep_engine.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"
#include "wetroad/version.hpp"

namespace wr {
namespace {

std::optional<nlohmann::json> read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // writes are atomic, so this is a foreign file: treat the run as not finished
  }
}

}  // namespace

std::string SweepCheckpoint::run_path(int index) const {
  char name[32];
  std::snprintf(name, sizeof name, "/run-%04d.json", index);
  return dir_ + name;
}

void SweepCheckpoint::check(const nlohmann::json& spec, bool resume) const {
  if (!resume) {
    if (std::filesystem::exists(dir_))
      throw InputError(dir_, "a checkpoint of an earlier sweep exists: continue it with --resume, or remove it");
    return;
  }
  const auto stored = read_json(dir_ + "/sweep.json");
  if (stored && (*stored)["spec"] != spec)
    throw InputError(dir_ + "/sweep.json", "--resume with different sweep parameters than the checkpointed sweep");
}

void SweepCheckpoint::start(const nlohmann::json& spec) const {
  std::filesystem::create_directories(dir_);
  write_text_atomically(dir_ + "/sweep.json", nlohmann::json({{"spec", spec}, {"version", kVersion}}).dump(2) + "\n");
}

std::map<int, nlohmann::json> SweepCheckpoint::finished(int count) const {
  std::map<int, nlohmann::json> done;
  for (int i = 0; i < count; ++i)
    if (auto r = read_json(run_path(i)); r && r->value("index", -1) == i) done[i] = std::move(*r);
  return done;
}

void SweepCheckpoint::save(int index, const nlohmann::json& record) const {
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

}  // namespace wr
