#pragma once
// Refuse an allocation that cannot fit before trying it, so that a huge dimension ends with a
// clear message instead of std::bad_alloc or the OOM killer.
#include <cstddef>
#include <string>

namespace wr {

// Physical memory of this machine, bytes.
std::size_t physical_memory_bytes();

// Bytes for `count` elements of `element_bytes` each, times `copies` working copies.
// Throws InputError(source, ...) on overflow or when the total exceeds physical memory.
std::size_t require_memory(std::size_t count, std::size_t element_bytes, double copies,
                           const std::string& source, const std::string& what);

// nx*ny with an overflow check; throws InputError(source, ...) when it does not fit size_t.
std::size_t checked_cells(std::size_t nx, std::size_t ny, const std::string& source);

std::string human_bytes(double bytes);

}  // namespace wr
