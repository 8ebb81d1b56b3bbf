#pragma once
// The options of a contact scene (lib/scene/contact_scene.hpp), registered once for every
// command that runs one: `contact`, `sweep-coverage`, `sweep-roughness`. Each command starts
// from its own defaults (the scene it holds before parsing).
#include <string>

#include <CLI/CLI.hpp>

#include "lib/scene/contact_scene.hpp"

namespace wr::app {

struct SceneCli {
  ContactScene scene;
  std::string thickness;      // m or "inf"; empty: the block height
  std::string amg = "auto";
  std::string solver = "auto";
  bool vertical = false;
  CLI::Option *uz = nullptr, *ux = nullptr;
};

// --uz --ux --steps --shear-steps --to-peak --refine --height --layers --coarsen --E --nu --damping
// --extrapolate --face-modes --coarse-start --max-penetration --cutbacks --predictor --ksp-rtol
// --tol --spectral-tol --max-iterations --iteration --curvature --vertical --facet-normals --facet-band --block-normals
// --amg --thickness.
void add_scene_options(CLI::App& app, SceneCli& c);
// After parsing: the texts (--thickness, --amg, --vertical) into the scene, and a shear phase of
// 0 steps made "as many as the normal phase". InputError naming the option on a bad text.
void finish_scene_options(SceneCli& c);

}  // namespace wr::app
