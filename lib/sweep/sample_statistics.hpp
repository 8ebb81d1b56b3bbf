#pragma once
// Statistics of independent realizations, as the sweeps report them.
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

// Two-sided 95 % Student t quantile for `dof` degrees of freedom (>= 1; NaN below).
double student_t95(int dof);

// {mean, std (n - 1), ci95 (t95(n-1) std / sqrt n), cov (std / |mean|, the thesis's s*), n};
// null entries for an empty sample, and std, ci95, cov null for a single value (one
// realization has no spread to report).
nlohmann::json sample_statistics(const std::vector<double>& v);

}  // namespace wr
