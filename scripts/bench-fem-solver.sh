#!/bin/sh
# Direct (sparse Cholesky: CHOLMOD) against AMG-preconditioned CG in the FEM's active-set solves,
# on one rank, over rough scenes of growing size: the crossover in nodes behind --solver auto
# (lib/fem/linear_solver.hpp). Each scene: an N x N default-spectrum surface (dx 0.1 mm), refine
# 1, pressed 2 steps to uz (normal problem), tol 1e-3. Prints nodes, wall and solve seconds,
# CG iterations and the area fraction of each solver (which must agree to the tolerance).
# Usage: scripts/bench-fem-solver.sh [WETROAD] [WORKDIR] [SIZES...]   (defaults: 16 32 48 64 96)
# Not part of make test: minutes.
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-solver}
shift 2 2>/dev/null || shift $#
SIZES=${*:-16 32 48 64 96}
mkdir -p "$W"
export OMP_NUM_THREADS=1
printf "%6s %9s %8s %10s %10s %8s %12s\n" size nodes solver wall_s solve_s cg_its area
for n in $SIZES; do
  [ -f "$W/s$n.h5" ] || "$BIN" synth --size "$n" --dx 1e-4 --h0 3e-4 --seed 1 -q -o "$W/s$n.h5"
  for solver in direct amg; do
    "$BIN" contact --surface "$W/s$n.h5" --model fem --problem normal --uz 2e-4 --steps 2 --refine 1 --tol 1e-3 \
      --solver "$solver" --json "$W/s${n}_$solver.json" -q > "$W/s${n}_$solver.log" 2>&1 || true
    /usr/bin/python3 - "$W/s${n}_$solver.json" "$n" "$solver" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
st = d["steps"][-1]
solve = sum(s.get("timings", {}).get("solve", 0) for s in d["steps"])
its = sum(s.get("linear_iterations", 0) for s in d["steps"])
print(f"{sys.argv[2]:>6} {d['nodes']:>9} {sys.argv[3]:>8} {d['wall_s']:>10.2f} {solve:>10.2f} {its:>8} "
      f"{st.get('area_fraction', float('nan')):>12.6f}")
PY
  done
done
