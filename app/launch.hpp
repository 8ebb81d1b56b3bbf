#pragma once
// Rank and size of an mpirun launch, read from the launcher's environment, for commands that
// decide before (or without) initialising MPI: the analytic and spectral contact models run on
// threads, and sweeps print their model choice once.
#include <algorithm>
#include <cstdlib>
#include <utility>

namespace wr::app {

inline std::pair<int, int> launch_rank_and_size() {
  auto get = [](const char* a, const char* b) {
    const char* v = std::getenv(a);
    if (!v) v = std::getenv(b);
    return v ? std::atoi(v) : -1;
  };
  const int rank = get("OMPI_COMM_WORLD_RANK", "PMI_RANK"), size = get("OMPI_COMM_WORLD_SIZE", "PMI_SIZE");
  return {std::max(rank, 0), std::max(size, 1)};
}

}  // namespace wr::app
