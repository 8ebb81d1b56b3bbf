#!/bin/sh
# The main job on the built-in default scene: synthesize the default asphalt-like surface
# (share/scenes/default-asphalt.json), analyze it, and fill it with rain water (30% coverage and
# the drained limit); then a shear test of an elastic block on a small gentle patch (4 mm, 40 x 40:
# the FEM on the full 300 x 300 default surface is a long job, see docs/performance.md); finally a
# small coverage sweep on the default surface sampled coarsely (32 x 32 over the same 30 mm tile,
# so that each FEM run takes seconds; contact forces along the obstacle's facet normals, see
# docs/validation.md), a roughness sweep over the thesis's dataset A on 16 x 16 surfaces (its
# surfaces' MPDs give the skid-number chart its points), the hysteresis friction mu(v) of tread
# rubber on the dry and the drained wet surface (flash temperature on) with the skid numbers under
# ASTM E274's water film at 20-100 km/h, the water's flow through the contact on the map, the same model's coverage
# and roughness sweeps (the skid-number prediction), and the HTML report of all of them.
# Outputs land in build/demo/.
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
"$BIN" friction "$OUT/surface.h5" --wet "$OUT/wet-limit.h5" --flash-temperature --band --json "$OUT/friction.json" \
  --out "$OUT/friction.h5" --plot "$OUT/friction.svg" --plot-q1 "$OUT/friction-q1.svg" --plot-squeeze "$OUT/squeeze.svg"
echo
"$BIN" flow "$OUT/surface.h5" --pressure 3e5 --json "$OUT/flow.json" --vti "$OUT/flow.vti"
echo
"$BIN" synth --size 40 --dx 1e-4 --h0 5e-5 --hurst 0.7 --q0-ratio 2 --seed 3 -o "$OUT/patch.h5" -q
OMP_NUM_THREADS=1 "$BIN" contact --surface "$OUT/patch.h5" --problem shear --uz 1.2e-3 --ux 8e-4 --steps 2 --refine 1 \
  --tol 1e-3 --json "$OUT/contact.json" --out "$OUT/contact.h5" --vtu "$OUT/contact.vtu"
echo
rm -rf "$OUT/sweep.h5" "$OUT/sweep.h5.runs"
OMP_NUM_THREADS=1 "$BIN" sweep-coverage --scene default --size 32 --dx 9.375e-4 --coverages 0 0.2 0.4 0.5 0.6 0.7 \
  --uz 1.5e-3 --ux 3e-3 --steps 2 --shear-steps 3 --tol 1e-3 --facet-normals --out "$OUT/sweep.h5" --csv "$OUT/sweep.csv" \
  --plots "$OUT/sweep-charts"
echo
rm -rf "$OUT/roughness.h5" "$OUT/roughness.h5.runs"
OMP_NUM_THREADS=1 "$BIN" sweep-roughness --dataset A --size 16 --dx 1.875e-3 --realizations 1 --uz 1.5e-3 --ux 3e-3 \
  --steps 4 --shear-steps 2 --tol 1e-3 --facet-normals --out "$OUT/roughness.h5" --csv "$OUT/roughness.csv" -q
echo "roughness sweep (thesis dataset A on 16 x 16 surfaces): $OUT/roughness.csv"
echo
rm -rf "$OUT/sweep-hysteresis.h5" "$OUT/sweep-hysteresis.h5.runs"
"$BIN" sweep-coverage --scene default --model hysteresis --flash-temperature --coverages 0 0.2 0.4 0.5 0.6 0.7 0.8 \
  --out "$OUT/sweep-hysteresis.h5" --csv "$OUT/sweep-hysteresis.csv" -q
echo "hysteresis coverage sweep (default surface, mu at 64 km/h): $OUT/sweep-hysteresis.csv"
rm -rf "$OUT/roughness-hysteresis.h5" "$OUT/roughness-hysteresis.h5.runs"
"$BIN" sweep-roughness --dataset A --realizations 3 --model hysteresis --flash-temperature \
  --out "$OUT/roughness-hysteresis.h5" --csv "$OUT/roughness-hysteresis.csv" -q
echo "hysteresis roughness sweep (thesis dataset A, 300 x 300, 3 realizations): $OUT/roughness-hysteresis.csv"
echo
"$BIN" report --friction "$OUT/friction.h5" --sweep "$OUT/sweep-hysteresis.h5" --sweep "$OUT/roughness-hysteresis.h5" \
  --sweep "$OUT/sweep.h5" --sweep "$OUT/roughness.h5" -o "$OUT/report.html"
echo
echo "demo outputs in $OUT: surface.h5 (height map), analysis.json/.h5 (texture summary + PSD),"
echo "  wet-30.h5 (30% water coverage), wet-limit.h5 (drained limit); 'wetroad analyze' reads the wet surfaces too;"
echo "  contact.json/.h5/.vtu (shear test of a block on patch.h5: forces, mu, contact maps, deformed block)"
echo "  friction.json/.h5/.svg (hysteresis mu(v) of tread rubber, dry and wet, skid numbers under the E274 film;"
echo "    friction-q1.svg: mu against the cut-off; squeeze.svg: the film's drainage against the time under the tyre)"
echo "  flow.json/.vti (the water's thin-film flow through the contact's gap on the map; open the .vti in ParaView)"
echo "  sweep.h5/.csv, sweep-charts/ (elastostatic friction against water coverage), roughness.h5/.csv (against h0),"
echo "  sweep-hysteresis.h5/.csv, roughness-hysteresis.h5/.csv (hysteresis friction against coverage and h0),"
echo "  report.html (mu(v), the sweeps and skid numbers against MPD; open it in a browser)"
