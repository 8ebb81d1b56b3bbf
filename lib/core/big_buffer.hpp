#pragma once
// Allocation of large numeric arrays (height maps, FFT buffers).
//
// Why: on the virtual machines wetroad runs on, the first touch of fresh memory costs more
// than the numerics (measured 0.33 s per 128 MiB with 4 KiB pages, 0.19 s with transparent
// huge pages). Arrays of 4 MiB and more are therefore 2 MiB aligned and advised to use huge
// pages; smaller ones come from the ordinary heap.
#include <cstddef>
#include <new>
#include <vector>

namespace wr {

void* allocate_big(std::size_t bytes);           // throws std::bad_alloc
void free_big(void* p, std::size_t bytes) noexcept;

template <class T>
struct BigBufferAllocator {
  using value_type = T;
  BigBufferAllocator() = default;
  template <class U>
  BigBufferAllocator(const BigBufferAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_big(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { free_big(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const BigBufferAllocator<U>&) const noexcept { return true; }
};

template <class T>
using BigArray = std::vector<T, BigBufferAllocator<T>>;
using BigVector = BigArray<double>;
using BigVectorSingle = BigArray<float>;

}  // namespace wr
