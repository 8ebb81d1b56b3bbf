#!/bin/sh
# The FEM at the thesis's scale: a dataset-A surface (300 x 300, dx 0.1 mm,
# H 0.7, q0 = 5 qL, h0 0.305 mm), cube M (3 cm), nu 0.45, face spacing dx / 2 (refine 2).
# Problem A (uz 9 mm in 2 steps) then Problem B (ux in shear steps) on 2 ranks; wall time and
# peak memory per rank from /usr/bin/time, per-step times and forces from --json.
# Usage: scripts/bench-fem-thesis.sh [WETROAD] [WORKDIR] [UX_M] [SHEAR_STEPS] [TOL]
# SHEAR_STEPS 0: Problem A alone. FEM_OPTS (environment): more contact options, e.g.
# FEM_OPTS="--damping 1.0".
# Long: tens of minutes on 2 cores. Not part of make test.
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-thesis}
UX=${3:-3e-3}
SHEAR_STEPS=${4:-3}
TOL=${5:-1e-3}
mkdir -p "$W"
# shellcheck source=scripts/fem-bench-env.sh
. "$(dirname "$0")/fem-bench-env.sh"
dataset_a_surface "$BIN" "$W"
PROBLEM="--problem shear --ux $UX --shear-steps $SHEAR_STEPS"
[ "$SHEAR_STEPS" -eq 0 ] && PROBLEM="--problem normal"
# shellcheck disable=SC2086
/usr/bin/time -f "wall %e s, peak memory per rank %M KB" $MPIRUN "$BIN" contact --surface "$W/A_3.05e-4.h5" \
  $PROBLEM --uz 9e-3 --steps 2 --refine 2 --tol "$TOL" \
  --json "$W/shear.json" ${FEM_OPTS:-} 2>&1 | tee "$W/shear.log"
python3 - "$W/shear.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
a = sum(s["wall_s"] for s in d["steps"] if s["ux"] == 0)
b = sum(s["wall_s"] for s in d["steps"] if s["ux"] != 0)
print(f"nodes {d['nodes']}, ranks {d['ranks']}: Problem A {a:.0f} s, Problem B {b:.0f} s, total {a + b:.0f} s")
for s in d["steps"]:
    print(f"  uz {s['uz']:.4g} ux {s['ux']:.4g}: Fz {s['fz']:.4e} mu {s['mu']:.4f} A/A0 {s['area_fraction']:.4f} "
          f"pen {s['max_penetration']:.2e} signorini {s['signorini_iterations']} cg {s['linear_iterations']} {s['wall_s']:.0f} s")
PY
