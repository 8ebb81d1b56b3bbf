#pragma once
// Benchmarks and long validations behind `wetroad bench ...` (never run by `make test`).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr::bench {

// synth + analyze of an N x N surface, in-process, in a forked child per size so that the peak
// resident memory of each size is its own. Reports the best of `repeats` wall times per phase.
nlohmann::json speed(const std::vector<std::size_t>& sizes, int repeats, int threads, bool with_files,
                     const std::string& scratch_dir);

// Summit statistics of ensembles of synthesized surfaces (thesis Fig. 4.4): for each low-pass
// fraction of dataset C, `realizations` surfaces; ensemble mean of the measured summit mean and
// variance against eq. 4.5 at the prescribed alpha. Progress lines go to stderr.
nlohmann::json summit_ensemble(const std::vector<double>& fractions, int realizations, int threads);

}  // namespace wr::bench
