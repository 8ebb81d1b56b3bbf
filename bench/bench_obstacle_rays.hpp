#pragma once
// Ray casting against the FEM's triangulated obstacle: the lattice walk in use against CGAL's
// AABB tree (never run by `make test`).
#include <cstddef>

#include <nlohmann/json.hpp>

namespace wr::bench {

// `rays` rays from above an n x n default-scene surface, downward within max_tilt_deg of the
// vertical (contact normals of road textures stay within ~40 degrees), cast by both methods:
// build and query times, rays per second, and the largest difference of the hits' distances.
nlohmann::json obstacle_rays(std::size_t n, std::size_t rays, double max_tilt_deg, unsigned seed);

}  // namespace wr::bench
