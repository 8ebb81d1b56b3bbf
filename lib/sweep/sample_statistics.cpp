#include "lib/sweep/sample_statistics.hpp"

#include <cmath>
#include <limits>

namespace wr {

double student_t95(int dof) {
  static const double t[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                             2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                             2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return std::numeric_limits<double>::quiet_NaN();
  if (dof <= 30) return t[dof - 1];
  return 1.960 + 2.4 / dof;  // within 0.2 % of the exact quantile beyond 30
}

nlohmann::json sample_statistics(const std::vector<double>& v) {
  const std::size_t n = v.size();
  if (n == 0) return {{"mean", nullptr}, {"std", nullptr}, {"ci95", nullptr}, {"cov", nullptr}, {"n", 0}};
  double m = 0;
  for (double x : v) m += x;
  m /= double(n);
  double ss = 0;
  for (double x : v) ss += (x - m) * (x - m);
  if (n == 1) return {{"mean", m}, {"std", nullptr}, {"ci95", nullptr}, {"cov", nullptr}, {"n", 1}};  // no spread
  const double sd = std::sqrt(ss / double(n - 1));
  const double ci = student_t95(int(n) - 1) * sd / std::sqrt(double(n));
  return {{"mean", m},
          {"std", sd},
          {"ci95", ci},
          {"cov", m != 0 ? nlohmann::json(sd / std::abs(m)) : nlohmann::json(nullptr)},
          {"n", n}};
}

}  // namespace wr
