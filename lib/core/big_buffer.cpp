#include "lib/core/big_buffer.hpp"

#include <sys/mman.h>

#include <cstdlib>

namespace wr {
namespace {
constexpr std::size_t kHuge = std::size_t(2) << 20;
constexpr std::size_t kBig = 2 * kHuge;
std::size_t rounded(std::size_t bytes) { return (bytes + kHuge - 1) / kHuge * kHuge; }
}  // namespace

void* allocate_big(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  void* p = bytes < kBig ? std::malloc(bytes) : std::aligned_alloc(kHuge, rounded(bytes));
  if (!p) throw std::bad_alloc();
  if (bytes >= kBig) madvise(p, rounded(bytes), MADV_HUGEPAGE);
  return p;
}

void free_big(void* p, std::size_t) noexcept { std::free(p); }

}  // namespace wr
