#!/bin/sh
# The main job on the built-in default scene: synthesize the default asphalt-like surface
# (share/scenes/default-asphalt.json) and analyze it. Outputs land in build/demo/.
set -eu
BIN=${BIN:-build/bin/wetroad}
OUT=${OUT:-build/demo}
mkdir -p "$OUT"
"$BIN" synth --scene default -o "$OUT/surface.h5"
echo
"$BIN" analyze "$OUT/surface.h5" --json "$OUT/analysis.json" --out "$OUT/analysis.h5"
echo
echo "demo outputs: $OUT/surface.h5 (height map), $OUT/analysis.json, $OUT/analysis.h5 (summary + PSD)"
