#!/bin/sh
# A shear test killed with SIGKILL in its shear phase and restarted from its checkpoint
# (--restart) ends with the uninterrupted run's curve exactly: every step's forces, mu, contact
# fraction and iteration counts, compared as written (17 digits). With the matrix-free multigrid
# (--solver gmg) nothing carries between load steps but what the checkpoint holds.
# Usage: contact_restart.sh WETROAD WORKDIR
set -eu
BIN=$1
W=$2
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
"$BIN" synth --size 16 --dx 1e-4 --h0 3e-5 --hurst 0.7 --q0-ratio 2 --seed 3 -o "$W/s.h5" -q
RUN="contact --surface $W/s.h5 --problem shear --uz 8e-4 --ux 9e-4 --steps 2 --shear-steps 6 --refine 2 --tol 1e-4
  --solver gmg -q"
curve() {  # the physics of every step, one field per line
  grep -o '"\(uz\|ux\|fz\|fx\|mu\|area_fraction\|signorini_iterations\|linear_iterations\)": *[-0-9.eE+]*' "$1"
}

# shellcheck disable=SC2086
"$BIN" $RUN --json "$W/whole.json"

# shellcheck disable=SC2086
"$BIN" $RUN --json "$W/cut.json" --checkpoint "$W/cp" &
pid=$!
i=0
# Generation 3: both normal steps and the first shear step converged.
while ! grep -qs "^generation \([3-9]\|1[0-9]\)$" "$W/cp"; do
  i=$((i + 1))
  [ $i -gt 1200 ] && { echo "no shear step checkpointed within 120 s"; kill -9 $pid; exit 1; }
  sleep 0.1
done
kill -9 $pid
wait $pid 2>/dev/null || true
[ -e "$W/cut.json" ] && { echo "FAIL: the killed run had already finished; nothing was restarted"; exit 1; }
echo "killed after $(grep generation "$W/cp") converged steps"

# A restart with another load is refused, naming --restart.
# shellcheck disable=SC2086
if "$BIN" $(echo "$RUN" | sed 's/--uz 8e-4/--uz 7e-4/') --restart "$W/cp" 2>"$W/err.txt"; then echo "FAIL: a restart with another --uz ran"; exit 1; fi
grep -q -- "--restart" "$W/err.txt" || { echo "FAIL: no word of --restart:"; cat "$W/err.txt"; exit 1; }

# shellcheck disable=SC2086
"$BIN" $RUN --json "$W/cut.json" --restart "$W/cp" --checkpoint "$W/cp"
curve "$W/whole.json" >"$W/whole.txt"
curve "$W/cut.json" >"$W/cut.txt"
[ "$(grep -c '"signorini_iterations"' "$W/whole.txt")" -eq 8 ] || { echo "FAIL: the uninterrupted run has not 8 steps"; exit 1; }
cmp "$W/whole.txt" "$W/cut.txt" || { echo "FAIL: the restarted curve differs"; diff "$W/whole.txt" "$W/cut.txt"; exit 1; }
echo "restarted curve identical to the uninterrupted one"

# A restart may shear further: the checkpoint of a run to half the displacement, in half the
# steps, continued with the whole run's options, ends with the uninterrupted curve exactly
# (ux 9e-4 = 2 x 4.5e-4 in binary, so the targets j 9e-4 / 6 and j 4.5e-4 / 3 are the same doubles).
# It may allow cutbacks the first did not: no step fails here, so the curve is the same.
HALF=$(echo "$RUN" | sed 's/--ux 9e-4/--ux 4.5e-4/; s/--shear-steps 6/--shear-steps 3/')
# shellcheck disable=SC2086
"$BIN" $HALF --json "$W/half.json" --checkpoint "$W/cph"
# shellcheck disable=SC2086
if "$BIN" $(echo "$HALF" | sed 's/--ux 4.5e-4/--ux 3e-4/') --restart "$W/cph" 2>"$W/err2.txt"; then
  echo "FAIL: a restart with a shorter --ux ran"; exit 1
fi
grep -q "has no step left" "$W/err2.txt" || { echo "FAIL: no word of the missing steps:"; cat "$W/err2.txt"; exit 1; }
# shellcheck disable=SC2086
"$BIN" $RUN --json "$W/on.json" --restart "$W/cph" --cutbacks 1
curve "$W/on.json" >"$W/on.txt"
cmp "$W/whole.txt" "$W/on.txt" || { echo "FAIL: the extended curve differs"; diff "$W/whole.txt" "$W/on.txt"; exit 1; }
# Its JSON says which steps were kept and what they were solved with.
tr -d ' \n' <"$W/on.json" | grep -q '"restart":{"checkpoint":"[^"]*cph","steps_kept":5,"their_options":{"--cutbacks":0,"--max-penetration":[-0-9.eE+]*,"--shear-steps":3,"--tol":0.0001,"--ux":0.00045}}' ||
  { echo "FAIL: no restart record in the JSON"; grep -A12 '"restart"' "$W/on.json"; exit 1; }
echo "extended curve identical to the uninterrupted one"
