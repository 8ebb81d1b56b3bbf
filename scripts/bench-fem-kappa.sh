#!/bin/sh
# The FEM's low-pressure kappa against h0 on dataset A (thesis sec. 5.2.3,
# Table C.1): 300 x 300 surfaces (dx 0.1 mm, H 0.7, q0 = 5 qL, seed 1), cube M (3 cm), nu 0.45,
# face spacing dx / 2 (refine 2), 2 ranks. Each h0 is pressed in 2 steps to uz = 7.2 h0, which
# puts A/A0 near 2 % and 8 %, inside the thesis's 15 % low-pressure range: in the small-slope
# limit A/A0 depends on uz / h0 alone, so the same multiple works for every h0.
# Every surface is also pressed by the spectral model (same triangulated obstacle and face
# spacing; 12 steps to the same uz), an independent answer that has no h0 dependence at all
# (small-slope theory scales); besides its own fitted kappa, the column "FEM/spec" compares the
# two at the FEM's contact fractions (scripts/area_load_match.py: fits at different loads differ).
# kappa is printed over both slope estimates (forward and central differences, see
# roads/height_stats.hpp), next to Table C.1 (share/thesis/roughness-tables.json).
# Usage: [TOL=t] [REFINE=r] scripts/bench-fem-kappa.sh [WETROAD] [WORKDIR] [LOG10_H0 ...]
#   default h0: Table C.1's six values. Finished h0 (WORKDIR/kA<log h0>.json) are not redone.
#   TOL: the Signorini tolerance; default 1e-3, and 3e-4 for log h0 above -3.4 (the two
#   steepest surfaces, rms slope > 1.5), where 1e-3 leaves nodes deeper than the penetration
#   limit (the step fails).
#   REFINE: the face refinement of both models (default 2, the thesis's dGamma = dtheta / 2);
#   runs at 1 and 2 give a Richardson estimate of the mesh-converged kappa, 2 k(2) - k(1) at
#   the first order observed on a patch (docs/validation.md).
# Long: 15-30 min per h0 on 2 cores, ~9 GB. Not part of make test.
# $MPIRUN and the case lists split into words on purpose.
# shellcheck disable=SC2086
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-kappa}
if [ $# -ge 2 ]; then shift 2; else shift $#; fi
LOGS=${*:--4.27 -4.02 -3.77 -3.52 -3.27 -3.15}
TABLES=$(dirname "$0")/../share/thesis/roughness-tables.json
mkdir -p "$W"
export OMP_NUM_THREADS=1
MPIRUN="mpirun -np 2"
[ "$(id -u)" -eq 0 ] && MPIRUN="mpirun --allow-run-as-root -np 2"
refine=${REFINE:-2}
for lg in $LOGS; do
  h0=$(python3 -c "print('%.4g' % 10**($lg))")
  uz=$(python3 -c "print('%.4g' % (7.2 * 10**($lg)))")
  tol=${TOL:-$(python3 -c "print('3e-4' if $lg > -3.4 else '1e-3')")}
  [ -f "$W/A$lg.h5" ] ||
    "$BIN" synth --size 300 --dx 1e-4 --h0 "$h0" --hurst 0.7 --q0-ratio 5 --seed 1 -o "$W/A$lg.h5" -q
  [ -f "$W/sA$lg.json" ] ||
    "$BIN" contact --surface "$W/A$lg.h5" --model spectral --problem normal --uz "$uz" --steps 12 --refine "$refine" \
      --json "$W/sA$lg.json" -q 2>/dev/null
  if [ ! -f "$W/kA$lg.json" ]; then
    echo "log10 h0 $lg: h0 $h0 m, uz $uz m, refine $refine, tol $tol ($(date +%T))"
    /usr/bin/time -f "wall %e s, peak memory per rank %M KB" $MPIRUN "$BIN" contact --surface "$W/A$lg.h5" \
      --problem normal --uz "$uz" --steps 2 --refine "$refine" --tol "$tol" --json "$W/kA$lg.json" > "$W/kA$lg.log" 2>&1 ||
      echo "  failed: see $W/kA$lg.log"
  fi
done
python3 - "$(dirname "$0")" "$W" "$TABLES" $LOGS <<'PY'
import json, os, sys
sys.path.insert(0, sys.argv[1])
from area_load_match import matched
w, tables, logs = sys.argv[2], sys.argv[3], sys.argv[4:]
c1 = json.load(open(tables))["datasets"]["A"]["table_c1"]
thesis = dict(zip(c1["log10_h0"], c1["kappa"]))
def load(path):
    return json.load(open(path)) if os.path.exists(path) else None
def kappas(d, central):
    # kappa over the central slope: sigma* ~ 1 / slope, so kappa scales with the slopes' ratio
    low = (d.get("area_load_fit") or {}).get("low_pressure") or {}
    k = low.get("kappa", 0)
    areas = [s["area_fraction"] for s in d["steps"] if s["ux"] == 0 and s["converged"]]
    return k, k * central / d["rms_slope"], areas
print("kappa = A/A0 / sigma*, sigma* = sigma0 / (E* slope); fwd: forward-difference slope, cen: central")
print(f"{'log h0':>7} {'slope fwd':>9} {'cen':>6} {'A/A0 steps':>14} {'FEM fwd':>8} {'FEM cen':>8} "
      f"{'spec fwd':>8} {'spec cen':>8} {'FEM/spec':>8} {'C.1':>5} {'FEM wall':>9} {'tol':>6}")
nan = float("nan")
for lg in logs:
    fem, spec = load(f"{w}/kA{lg}.json"), load(f"{w}/sA{lg}.json")
    if fem is None:
        print(f"{lg:>7}  (no FEM result)"); continue
    if fem["status"] != "ok":
        first = next((st["message"] for st in fem["steps"] if not st["converged"]), "")
        print(f"{lg:>7} {fem['rms_slope']:9.4f}  FEM failed after {fem['wall_s']:.0f} s: {first}"); continue
    # Both runs read the same surface; older JSON lacks the central slope, the other may have it.
    central = next((d["rms_slope_central"] for d in (fem, spec) if d and "rms_slope_central" in d), nan)
    kf, kfc, areas = kappas(fem, central)
    ks, ksc, _ = kappas(spec, central) if spec else (nan, nan, None)
    # FEM over spectral A/A0 / sigma* at the FEM's steps (mean), where the spectral curve reaches
    ratios = [k / kr for _, k, kr in matched(fem, spec) if kr] if spec else []
    ratio = sum(ratios) / len(ratios) if ratios else nan
    print(f"{lg:>7} {fem['rms_slope']:9.4f} {central:6.3f} {' '.join('%.4f' % a for a in areas):>14} "
          f"{kf:8.3f} {kfc:8.3f} {ks:8.3f} {ksc:8.3f} {ratio:8.3f} {thesis.get(float(lg), nan):5.2f} {fem['wall_s']:8.0f}s "
          f"{fem.get('provenance', {}).get('parameters', {}).get('tolerance', nan):6.0e}")
PY
