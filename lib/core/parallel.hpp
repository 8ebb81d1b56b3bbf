#pragma once
// Deterministic shared-memory parallel loops.
//
// parallel_chunks(n, chunks, threads, fn) splits [0, n) into `chunks` contiguous pieces that
// depend only on n and chunks, never on the thread count, and calls fn(chunk, begin, end) for
// each piece on up to `threads` threads (<= 0: all hardware threads). Callers keep one partial
// result per chunk and combine them in chunk order, so results are bit-identical for any thread
// count. The first exception thrown by fn is rethrown on the calling thread.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace wr {

int hardware_threads();  // lib/core/fft.cpp

// Default chunk count for loops over rows: enough pieces to balance two to a few dozen threads.
inline std::size_t default_chunks(std::size_t n) { return std::min<std::size_t>(n, 64); }

inline std::size_t chunk_begin(std::size_t n, std::size_t chunks, std::size_t c) { return n * c / chunks; }

template <class F>
void parallel_chunks(std::size_t n, std::size_t chunks, int threads, F&& fn) {
  if (n == 0 || chunks == 0) return;
  if (threads <= 0) threads = hardware_threads();
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(threads), chunks);
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (std::size_t c; (c = next.fetch_add(1)) < chunks;) {
      try {
        fn(c, chunk_begin(n, chunks, c), chunk_begin(n, chunks, c + 1));
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = chunks;
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// K sums over [0, n): f(k, acc) adds index k's terms into acc (std::array<double, K>). Each of
// the `chunks` pieces sums on its own and the pieces are added in chunk order, so the result is
// the same bits for any thread count.
template <std::size_t K, class F>
std::array<double, K> parallel_sums(std::size_t n, std::size_t chunks, int threads, F&& f) {
  std::vector<std::array<double, K>> part(std::max<std::size_t>(chunks, 1), std::array<double, K>{});
  parallel_chunks(n, chunks, threads, [&](std::size_t c, std::size_t b, std::size_t e) {
    std::array<double, K> a{};
    for (std::size_t k = b; k < e; ++k) f(k, a);
    part[c] = a;
  });
  std::array<double, K> sum{};
  for (const auto& a : part)
    for (std::size_t i = 0; i < K; ++i) sum[i] += a[i];
  return sum;
}

}  // namespace wr
