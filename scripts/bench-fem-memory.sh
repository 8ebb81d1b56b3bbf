#!/bin/sh
# Peak memory of the FEM at the thesis's scale (the delta_theta / 4 mesh in
# 24 GiB): the dataset-A surface of bench-fem-thesis.sh (300 x 300, dx 0.1 mm, h0 0.305 mm),
# pressed 4.5 mm for a few Signorini iterations (the step is stopped there on purpose: the
# peak is reached in the first AMG setup and solve), on 2 ranks, with the AMG hierarchy given.
# Prints nodes, the peak resident memory per rank (/usr/bin/time) and in all, and per node.
# Usage: scripts/bench-fem-memory.sh [WETROAD] [WORKDIR] [REFINE] [AMG] [ITERATIONS]
# e.g. REFINE 4, AMG lean: 3.93M nodes. Long: about 9 min at refine 4. Not part of make test.
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-memory}
REFINE=${3:-2}
AMG=${4:-auto}
ITERATIONS=${5:-2}
mkdir -p "$W"
# shellcheck source=scripts/fem-bench-env.sh
. "$(dirname "$0")/fem-bench-env.sh"
dataset_a_surface "$BIN" "$W"
TAG="r${REFINE}_$AMG"
# The step ends unconverged after ITERATIONS (exit 3, by design); the json keeps the mesh.
# $MPIRUN splits into words on purpose.
# shellcheck disable=SC2086
/usr/bin/time -o "$W/$TAG.time" -f "%M %e" $MPIRUN "$BIN" contact --surface "$W/A_3.05e-4.h5" --problem normal \
  --uz 4.5e-3 --steps 1 --refine "$REFINE" --tol 1e-3 --max-iterations "$ITERATIONS" --amg "$AMG" --trace \
  --json "$W/$TAG.json" > "$W/$TAG.log" 2>&1 || true
python3 - "$W/$TAG.json" "$W/$TAG.time" "$AMG" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
kib, wall = open(sys.argv[2]).read().split()[-2:]
per_rank = float(kib) * 1024
total = per_rank * d["ranks"]
print(f"refine {d['provenance']['parameters']['refine']}, {d['nodes']} nodes, amg {d.get('amg', sys.argv[3])}: "
      f"peak {per_rank / 2**30:.2f} GiB per rank, {total / 2**30:.2f} GiB in all, "
      f"{total / d['nodes'] / 1024:.2f} KiB per node, wall {float(wall):.0f} s")
PY
