#include "lib/core/richardson.hpp"

#include <cmath>
#include <stdexcept>

namespace wr {

std::optional<RichardsonEstimate> richardson_three(double f0, double f1, double f2, double ratio) {
  if (!(ratio > 1)) throw std::invalid_argument("richardson_three: the refinement ratio must exceed 1");
  if (!std::isfinite(f0) || !std::isfinite(f1) || !std::isfinite(f2)) return std::nullopt;
  const double d01 = f0 - f1, d12 = f1 - f2;
  if (d12 == 0) {
    if (d01 != 0) return std::nullopt;
    return RichardsonEstimate{0, f2, 0};
  }
  const double q = d01 / d12;  // r^p
  if (!(q > 1)) return std::nullopt;
  constexpr double kSafety = 1.25;
  RichardsonEstimate e;
  e.order = std::log(q) / std::log(ratio);
  e.limit = f2 - d12 / (q - 1);
  e.error = kSafety * std::abs(d12) / (q - 1);
  return e;
}

}  // namespace wr
