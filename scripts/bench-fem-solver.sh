#!/bin/sh
# Direct (sparse Cholesky: CHOLMOD) against AMG-preconditioned CG in the FEM's active-set solves,
# on one rank, over rough scenes of growing size: the crossover in nodes behind --solver auto
# (lib/fem/linear_solver.hpp). Each size: SEEDS default-spectrum surfaces N x N (dx 0.1 mm,
# h0 0.3 mm), refine 1, pressed in 2 steps to uz 0.2 mm (normal problem), tol 1e-3. Prints per
# size and solver the nodes, the summed solve and total seconds over the seeds, CG iterations, and
# the largest difference of the final area fraction between the solvers (both meet the tolerance).
# PROBLEM=shear: then sheared 0.4 mm in 2 more steps (the shear test's systems change more from
# one Signorini iteration to the next, and a kept factor preconditions them less well).
# Usage: [PROBLEM=shear] scripts/bench-fem-solver.sh [WETROAD] [WORKDIR] [SEEDS] [SIZES...]
#   (defaults: 3; 16 24 32 48 64). Not part of make test: about 5 minutes with the defaults.
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-solver}
SEEDS=${3:-3}
shift 3 2>/dev/null || shift $#
SIZES=${*:-16 24 32 48 64}
PROBLEM=${PROBLEM:-normal}
LOAD="--problem normal"
[ "$PROBLEM" = shear ] && LOAD="--problem shear --ux 4e-4 --shear-steps 2"
mkdir -p "$W"
export OMP_NUM_THREADS=1
for n in $SIZES; do
  seed=1
  while [ "$seed" -le "$SEEDS" ]; do
    s="$W/s${n}_$seed"
    [ -f "$s.h5" ] || "$BIN" synth --size "$n" --dx 1e-4 --h0 3e-4 --seed "$seed" -q -o "$s.h5"
    for solver in direct amg; do
      # shellcheck disable=SC2086  # LOAD splits into options on purpose
      "$BIN" contact --surface "$s.h5" --model fem $LOAD --uz 2e-4 --steps 2 --refine 1 --tol 1e-3 \
        --solver "$solver" --json "${s}_${PROBLEM}_$solver.json" > "${s}_${PROBLEM}_$solver.log" 2>&1 || true
    done
    seed=$((seed + 1))
  done
done
/usr/bin/python3 - "$W" "$SEEDS" "$PROBLEM" $SIZES <<'PY'
import json, re, sys
w, seeds, problem, sizes = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
print(f"{'size':>5} {'nodes':>7} {'solver':>7} {'solve_s':>8} {'total_s':>8} {'cg_its':>7} {'signorini':>9} {'max d(A/A0)':>11}")
for n in sizes:
    area = {}
    for solver in ("direct", "amg"):
        solve = total = 0.0
        its = sig = 0
        nodes = 0
        for seed in range(1, seeds + 1):
            base = f"{w}/s{n}_{seed}_{problem}_{solver}"
            d = json.load(open(base + ".json"))
            nodes = d["nodes"]
            log = open(base + ".log").read()
            m = re.search(r"solve ([0-9.]+)\s+total ([0-9.]+)", log)
            solve += float(m.group(1)); total += float(m.group(2))
            its += sum(s["linear_iterations"] for s in d["steps"])
            sig += sum(s["signorini_iterations"] for s in d["steps"])
            area[(solver, seed)] = d["steps"][-1]["area_fraction"]
        print(f"{n:>5} {nodes:>7} {solver:>7} {solve:>8.2f} {total:>8.2f} {its:>7} {sig:>9}", end="")
        if solver == "amg":
            print(f" {max(abs(area[('direct', s)] - area[('amg', s)]) for s in range(1, seeds + 1)):>11.2e}")
        else:
            print()
PY
