#!/bin/sh
# The main job on the built-in default scene: synthesize the default asphalt-like surface
# (share/scenes/default-asphalt.json), analyze it, and fill it with rain water (30% coverage and
# the drained limit). Outputs land in build/demo/.
set -eu
BIN=${BIN:-build/bin/wetroad}
OUT=${OUT:-build/demo}
mkdir -p "$OUT"
"$BIN" synth --scene default -o "$OUT/surface.h5"
echo
"$BIN" analyze "$OUT/surface.h5" --json "$OUT/analysis.json" --out "$OUT/analysis.h5"
echo
"$BIN" fill "$OUT/surface.h5" --coverage 0.3 -o "$OUT/wet-30.h5" --json "$OUT/wet-30.json"
echo
"$BIN" fill "$OUT/surface.h5" --limit -o "$OUT/wet-limit.h5" --json "$OUT/wet-limit.json"
echo
echo "demo outputs in $OUT: surface.h5 (height map), analysis.json/.h5 (texture summary + PSD),"
echo "  wet-30.h5 (30% water coverage), wet-limit.h5 (drained limit); 'wetroad analyze' reads the wet surfaces too"
