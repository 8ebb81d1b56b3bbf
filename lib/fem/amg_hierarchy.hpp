#pragma once
// Which AMG hierarchy preconditions the FEM's CG, chosen by the memory the run needs. Why: on
// 2 ranks the standard hierarchy (smoothed aggregation, PETSc's scalable PtAP) takes about
// 8.1-8.4 KiB per node, so the thesis's delta_theta / 4 mesh (300 x 300 at refine 4: 3.93M
// nodes) would need about 33 GB; the lean one (unsmoothed aggregation, all-at-once PtAP) takes
// 5.3-5.4 KiB per node and sets up and solves that mesh in 19.5 GiB. Lean costs more CG
// iterations on small scenes (100 x 100, refine 2: 1909 against 1233), so it is used only where
// the standard one would not fit. On one rank the products stay PETSc's scalable ones (the
// all-at-once algorithm is for parallel matrices only).
#include <string>

namespace wr {

enum class AmgHierarchy { automatic, standard, lean };

// Resident bytes per independent FEM node, all ranks together, rounded up from the 300 x 300
// dataset-A scene (`scripts/bench-fem-memory.sh`, 2 ranks, 2026-12-03): standard 8.09-8.35 KiB
// at 1.05M nodes; lean 5.30-5.42 KiB at 1.05M and 5.21-5.25 KiB at 3.93M nodes.
inline constexpr double kStandardAmgBytesPerNode = 8.6e3;
inline constexpr double kLeanAmgBytesPerNode = 5.6e3;
// automatic picks standard while its estimate stays within this share of the host's memory.
inline constexpr double kStandardAmgMemoryShare = 0.8;

// Bytes a block of `nodes` independent nodes needs with hierarchy `h` (standard or lean).
double fem_memory_estimate(double nodes, AmgHierarchy h);

// `requested` unless it is automatic; then standard when fem_memory_estimate(host_nodes,
// standard) <= kStandardAmgMemoryShare x host_memory_bytes, else lean. host_nodes: the nodes
// owned by the ranks on this host.
AmgHierarchy resolve_amg_hierarchy(AmgHierarchy requested, double host_nodes, double host_memory_bytes);

// "auto", "standard", "lean"; InputError(option, ...) for anything else.
AmgHierarchy parse_amg_hierarchy(const std::string& text, const std::string& option);
const char* amg_hierarchy_name(AmgHierarchy h);

}  // namespace wr
