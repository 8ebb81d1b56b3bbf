#pragma once
// The squeeze-out's two rungs side by side (issue 55): the mean field the skid model runs on
// (Persson's load-separation and the effective-medium conductance, from the map's spectrum) and
// the map itself (the spectral contact solver's load-separation curve and the Reynolds
// conductance of its gap, lib/flow), for the same elastic rubber, film and rib. Never run by
// `make test`.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr::bench {

struct SqueezeBenchSetup {
  std::vector<double> h0 = {7.24e-5, 1.7e-4, 3.02e-4};  // dataset A's smoothest, a middle one, the default
  std::size_t n = 300;           // default scene: 30 mm tile, H 0.7, q0 = 5 qL, q1 = Nyquist
  std::uint64_t seed = 1;
  double young = 10e6, poisson = 0.45;  // an elastic rubber for both rungs
  double pressure = 0.3e6;       // sigma0, Pa
  double film = 0.5e-3;          // m
  std::vector<double> drainage = {0.018, 0.15};  // the two E274 tyres' drainage lengths, m
  double patch_time = 0.19 / 17.9;  // s: E274 at 64 km/h
  int ladder_points = 25;        // pressures of the map's load-separation curve
  int threads = 0;
};

// Per surface and drainage length: MPD-free summary rows {h0, drainage_length, mean_field {...},
// map {...}} with the times to 1 % and 90 % asperity load, the mean load share over the patch
// time, and the equilibrium separation and contact; plus the map's ladder (p, u, A, K).
nlohmann::json squeeze_rungs(const SqueezeBenchSetup& setup);

}  // namespace wr::bench
