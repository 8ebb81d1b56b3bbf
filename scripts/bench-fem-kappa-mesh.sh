#!/bin/sh
# Where the FEM's low-pressure kappa error sits: face refinement against the
# bulk's grading (--layers), on a gentle 100 x 100 patch of dataset A's spectrum (dx 0.1 mm,
# h0 15 um, rms slope 0.09), pressed 40 um in 2 steps (A/A0 ~2 % and ~5 %), 2 ranks.
# The reference is the spectral model on the same triangulated obstacle at the same face
# spacing. The FEM is compared with it at the same A/A0, not through fitted kappas: on a patch
# this small A/A0 / sigma* falls from 3.0 at 1.4 % contact to 2.3 at 10 %, so kappas fitted at
# different loads differ by more than the mesh error. The spectral curve (12 steps) is
# interpolated linearly at each FEM step's A/A0.
# Usage: scripts/bench-fem-kappa-mesh.sh [WETROAD] [WORKDIR] [REFINE:LAYERS ...]
#   default cases: 1:1 1:2 1:4 1:8 2:1 2:2 2:4 2:8 4:1 4:2 (about 35 min on 2 cores, 2 GB).
#   Finished cases (WORKDIR/fem-r<R>-l<L>.json) are not redone. Not part of make test.
# $MPIRUN and the case lists split into words on purpose.
# shellcheck disable=SC2086
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-fem-kappa-mesh}
if [ $# -ge 2 ]; then shift 2; else shift $#; fi
CASES=${*:-1:1 1:2 1:4 1:8 2:1 2:2 2:4 2:8 4:1 4:2}
mkdir -p "$W"
export OMP_NUM_THREADS=1
MPIRUN="mpirun -np 2"
[ "$(id -u)" -eq 0 ] && MPIRUN="mpirun --allow-run-as-root -np 2"
S="$W/patch.h5"
[ -f "$S" ] || "$BIN" synth --size 100 --dx 1e-4 --h0 1.5e-5 --hurst 0.7 --q0-ratio 5 --seed 1 -o "$S" -q
for c in $CASES; do
  r=${c%%:*}
  l=${c##*:}
  [ -f "$W/spectral-r$r.json" ] ||
    "$BIN" contact --surface "$S" --model spectral --problem normal --uz 6e-5 --steps 12 --refine "$r" \
      --json "$W/spectral-r$r.json" -q 2>/dev/null
  if [ ! -f "$W/fem-r$r-l$l.json" ]; then
    echo "refine $r, layers $l ($(date +%T))"
    $MPIRUN "$BIN" contact --surface "$S" --problem normal --uz 4e-5 --steps 2 --refine "$r" --layers "$l" \
      --tol 1e-3 --json "$W/fem-r$r-l$l.json" > "$W/fem-r$r-l$l.log" 2>&1 || echo "  failed: see $W/fem-r$r-l$l.log"
  fi
done
python3 - "$(dirname "$0")" "$W" $CASES <<'PY'
import json, os, sys
sys.path.insert(0, sys.argv[1])
from area_load_match import matched
w, cases = sys.argv[2], sys.argv[3:]
print("FEM A/A0 / sigma* over the spectral model's at the same A/A0 and face spacing")
print(f"{'refine':>6} {'layers':>6} {'nodes':>8} {'wall':>7}  per step: A/A0, FEM, spectral, ratio")
for c in cases:
    r, l = c.split(":")
    fem_path, spec_path = f"{w}/fem-r{r}-l{l}.json", f"{w}/spectral-r{r}.json"
    if not (os.path.exists(fem_path) and os.path.exists(spec_path)):
        print(f"{r:>6} {l:>6}  (no result)"); continue
    fem, spec = json.load(open(fem_path)), json.load(open(spec_path))
    if fem["status"] != "ok":
        print(f"{r:>6} {l:>6}  FEM failed: see {w}/fem-r{r}-l{l}.log"); continue
    cols = [f"{a:.4f} {k:.3f} {ks:.3f} {k / ks:.3f}" if ks else f"{a:.4f} {k:.3f} (outside the spectral curve)"
            for a, k, ks in matched(fem, spec)]
    print(f"{r:>6} {l:>6} {fem['nodes']:>8} {fem['wall_s']:6.0f}s  " + " | ".join(cols))
PY
