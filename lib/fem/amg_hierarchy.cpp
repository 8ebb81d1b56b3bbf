#include "lib/fem/amg_hierarchy.hpp"

#include "lib/core/errors.hpp"

namespace wr {

double fem_memory_estimate(double nodes, AmgHierarchy h) {
  return nodes * (h == AmgHierarchy::lean ? kLeanAmgBytesPerNode : kStandardAmgBytesPerNode);
}

AmgHierarchy resolve_amg_hierarchy(AmgHierarchy requested, double host_nodes, double host_memory_bytes) {
  if (requested != AmgHierarchy::automatic) return requested;
  const bool fits = fem_memory_estimate(host_nodes, AmgHierarchy::standard) <= kStandardAmgMemoryShare * host_memory_bytes;
  return fits ? AmgHierarchy::standard : AmgHierarchy::lean;
}

AmgHierarchy parse_amg_hierarchy(const std::string& text, const std::string& option) {
  if (text == "auto") return AmgHierarchy::automatic;
  if (text == "standard") return AmgHierarchy::standard;
  if (text == "lean") return AmgHierarchy::lean;
  throw InputError(option, "must be auto, standard or lean (got '" + text + "')");
}

const char* amg_hierarchy_name(AmgHierarchy h) {
  switch (h) {
    case AmgHierarchy::standard: return "standard";
    case AmgHierarchy::lean: return "lean";
    default: return "auto";
  }
}

}  // namespace wr
