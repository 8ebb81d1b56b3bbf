#include "roads/reference_plates.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace wr {

namespace {

// Length (samples) of the flat run starting at h[0] and stepping by `step` (+1 or -1), and its
// level (the mean of its valid samples).
struct Run {
  std::size_t length = 0;
  double level = 0;
};

Run flat_run(const double* h, const unsigned char* dropout, std::size_t n, std::ptrdiff_t step, double flatness) {
  Run r;
  double lo = INFINITY, hi = -INFINITY, sum = 0;
  std::size_t valid = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = step > 0 ? k : n - 1 - k;
    if (!dropout[i]) {
      const double nlo = std::min(lo, h[i]), nhi = std::max(hi, h[i]);
      if (nhi - nlo > flatness) break;
      lo = nlo;
      hi = nhi;
      sum += h[i];
      ++valid;
    }
    r.length = k + 1;
  }
  r.level = valid ? sum / double(valid) : NAN;
  return r;
}

double median_of_valid(const double* h, const unsigned char* dropout, std::size_t begin, std::size_t end) {
  std::vector<double> v;
  for (std::size_t i = begin; i < end; ++i)
    if (!dropout[i]) v.push_back(h[i]);
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

PlateCut find_reference_plates(const double* h, const unsigned char* dropout, std::size_t n, double dx,
                               const PlateOptions& opt) {
  PlateCut cut;
  if (n < 4 || !(dx > 0)) return cut;
  const auto samples = [&](double length) { return std::size_t(std::ceil(length / dx - 1e-9)); };
  const std::size_t min_run = std::max<std::size_t>(2, samples(opt.min_length)), margin = samples(opt.margin);
  const Run head = flat_run(h, dropout, n, +1, opt.flatness), tail = flat_run(h, dropout, n, -1, opt.flatness);
  const std::size_t head_cut = head.length >= min_run ? std::min(n, head.length + margin) : 0;
  const std::size_t tail_cut = tail.length >= min_run ? std::min(n, tail.length + margin) : 0;
  if (head_cut + tail_cut + n / 4 > n) return cut;  // a flat record, not a record with plates
  const double road = median_of_valid(h, dropout, head_cut, n - tail_cut);
  if (head_cut && std::abs(head.level - road) >= opt.min_step) cut.start = head_cut;
  if (tail_cut && std::abs(tail.level - road) >= opt.min_step) cut.end = tail_cut;
  return cut;
}

}  // namespace wr
