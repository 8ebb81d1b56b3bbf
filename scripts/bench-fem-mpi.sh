#!/bin/sh
# FEM speedup on 2 MPI ranks against 1: the same contact run on each, timed by
# its own --json (wall_s: mesh, assembly and solve) and by /usr/bin/time (the whole process,
# with peak memory per rank). The two runs take slightly different paths (GAMG's aggregates
# follow the partition), so the Signorini and CG counts are printed with the times, and the
# speedup per CG iteration beside the plain one. Agreement of mu and A/A0 at a tight tolerance
# is a test (tests/contact_mpi.sh).
# Usage: scripts/bench-fem-mpi.sh [WETROAD] [WORKDIR] [SIZE] [REFINE] [TOL]
# Default scene: a 100 x 100 dataset-A-like patch (dx 0.1 mm, h0 0.1 mm, H 0.7, q0 = 5 qL,
# seed 5) pressed 1.5 mm in one step at refine 2 (~130k nodes), --tol 1e-3. SIZE 300 with
# seed 1 and h0 0.305 mm is the thesis's scene (bench-fem-thesis.sh); there 1 rank takes hours.
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-mpi}
SIZE=${3:-100}
REFINE=${4:-2}
TOL=${5:-1e-3}
mkdir -p "$W"
# shellcheck source=scripts/fem-bench-env.sh
. "$(dirname "$0")/fem-bench-env.sh"
S="$W/s$SIZE.h5"
[ -f "$S" ] || "$BIN" synth --size "$SIZE" --dx 1e-4 --h0 1e-4 --hurst 0.7 --q0-ratio 5 --seed 5 -o "$S" -q
for n in 1 2; do
  launch="$MPILAUNCH -np $n"
  echo "== $n rank(s): $launch wetroad contact --surface $S --problem normal --uz 1.5e-3 --steps 1 --refine $REFINE --tol $TOL"
  # shellcheck disable=SC2086
  /usr/bin/time -f "process wall %e s, peak memory per rank %M KB" -o "$W/time$n.txt" $launch "$BIN" contact \
    --surface "$S" --problem normal --uz 1.5e-3 --steps 1 --refine "$REFINE" --tol "$TOL" \
    --json "$W/r$n.json" ${FEM_OPTS:-} >"$W/r$n.log" 2>&1 || { tail -20 "$W/r$n.log"; exit 1; }
  cat "$W/time$n.txt"
done
python3 - "$W/r1.json" "$W/r2.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
def totals(d):
    s = d["steps"]
    return sum(x["signorini_iterations"] for x in s), sum(x["linear_iterations"] for x in s)
(sa, ca), (sb, cb) = totals(a), totals(b)
print(f"nodes {a['nodes']}, dofs {a['dofs']}")
print(f"1 rank : {a['wall_s']:.1f} s, {sa} Signorini / {ca} CG iterations ({1e3 * a['wall_s'] / ca:.1f} ms per CG)")
print(f"2 ranks: {b['wall_s']:.1f} s, {sb} Signorini / {cb} CG iterations ({1e3 * b['wall_s'] / cb:.1f} ms per CG)")
print(f"speedup {a['wall_s'] / b['wall_s']:.2f}x (per CG iteration {(a['wall_s'] / ca) / (b['wall_s'] / cb):.2f}x)")
for x, y in zip(a["steps"], b["steps"]):
    print(f"  uz {x['uz']:.4g}: Fz {x['fz']:.6e} / {y['fz']:.6e} (relative {abs(x['fz'] - y['fz']) / x['fz']:.1e}), "
          f"A/A0 {x['area_fraction']:.6f} / {y['area_fraction']:.6f}")
PY
