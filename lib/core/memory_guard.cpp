#include "lib/core/memory_guard.hpp"

#include <unistd.h>

#include <cstdio>
#include <limits>

#include "lib/core/errors.hpp"

namespace wr {

std::size_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
}

std::string human_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f %s", bytes, units[u]);
  return buf;
}

std::size_t checked_cells(std::size_t nx, std::size_t ny, const std::string& source) {
  if (nx != 0 && ny > std::numeric_limits<std::size_t>::max() / nx)
    throw InputError(source, "dimension " + std::to_string(nx) + "x" + std::to_string(ny) +
                                 " overflows the address space");
  return nx * ny;
}

std::size_t require_memory(std::size_t count, std::size_t element_bytes, double copies,
                           const std::string& source, const std::string& what) {
  const double need = static_cast<double>(count) * static_cast<double>(element_bytes) * copies;
  const double have = static_cast<double>(physical_memory_bytes());
  if (need > have)
    throw InputError(source, what + " needs " + human_bytes(need) + " but this machine has " +
                                 human_bytes(have) + " of memory");
  return static_cast<std::size_t>(need);
}

}  // namespace wr
