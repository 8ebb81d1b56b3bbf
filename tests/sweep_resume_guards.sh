#!/bin/sh
# A resumed sweep never mixes runs: --resume is refused, with a one-line reason naming what
# changed, when the surface file has other content, when an option (here --sampling) differs,
# when sweep.json is missing or corrupt, and when a run record was edited; and while one
# process runs a sweep, a second one resuming it refuses instead of recomputing everything.
# Usage: sweep_resume_guards.sh WETROAD WORKDIR
set -eu
BIN=$1
W=$2
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
. "$(dirname "$0")/expect_error.sh"
RUNS="--coverages 0 0.3 --uz 1e-3 --ux 1e-3 --steps 1 --shear-steps 1 --model spectral -q"

# A surface file whose content changes under the same name.
"$BIN" synth --size 16 --dx 1.875e-3 --h0 1e-4 --seed 1 -o "$W/road.h5" -q
# shellcheck disable=SC2086
"$BIN" sweep-coverage --surface "$W/road.h5" $RUNS --out "$W/s.h5"
"$BIN" synth --size 16 --dx 1.875e-3 --h0 1e-4 --seed 2 -o "$W/road.h5" -q
# shellcheck disable=SC2086
expect_error "other content" sweep-coverage --surface "$W/road.h5" $RUNS --out "$W/s.h5" --resume

# An option that changes the surfaces: --sampling.
SYN="--size 16 --dx 1.875e-3 --h0 1e-4"
# shellcheck disable=SC2086
"$BIN" sweep-coverage $SYN $RUNS --out "$W/t.h5"
# shellcheck disable=SC2086
expect_error "surface.sampling" sweep-coverage $SYN --sampling thesis $RUNS --out "$W/t.h5" --resume

# An edited run record.
sed 's/"mu_peak": [-0-9.e]*/"mu_peak": 0.5/' "$W/t.h5.runs/run-0001.json" > "$W/edit.json"
cmp -s "$W/edit.json" "$W/t.h5.runs/run-0001.json" && { echo "FAIL: the edit changed nothing"; exit 1; }
cp "$W/t.h5.runs/run-0001.json" "$W/run-0001.orig"
cp "$W/edit.json" "$W/t.h5.runs/run-0001.json"
# shellcheck disable=SC2086
expect_error "checksum" sweep-coverage $SYN $RUNS --out "$W/t.h5" --resume
cp "$W/run-0001.orig" "$W/t.h5.runs/run-0001.json"
# shellcheck disable=SC2086
"$BIN" sweep-coverage $SYN $RUNS --out "$W/t.h5" --resume  # untouched: resumes

# A corrupt, then a deleted sweep spec.
echo "{ not json" > "$W/t.h5.runs/sweep.json"
# shellcheck disable=SC2086
expect_error "corrupt" sweep-coverage $SYN $RUNS --out "$W/t.h5" --resume
rm "$W/t.h5.runs/sweep.json"
# shellcheck disable=SC2086
expect_error "missing" sweep-coverage $SYN $RUNS --out "$W/t.h5" --resume

# Two processes on one sweep: the second refuses while the first holds the checkpoint.
LONG="--scene default --size 16 --dx 1.875e-3 --coverages 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 --uz 3e-3 --ux 1.5e-3
  --steps 2 --shear-steps 2 -q"
# shellcheck disable=SC2086
"$BIN" sweep-coverage $LONG --out "$W/u.h5" &
pid=$!
i=0
while [ ! -e "$W/u.h5.runs/sweep.json" ]; do
  i=$((i + 1))
  [ $i -gt 600 ] && { echo "FAIL: the first sweep did not start"; kill -9 $pid; exit 1; }
  sleep 0.1
done
if [ -e "$W/u.h5" ]; then echo "FAIL: the first sweep finished before the second could try"; exit 1; fi
# shellcheck disable=SC2086
expect_error "another wetroad process" sweep-coverage $LONG --out "$W/u.h5" --resume
wait $pid
[ -e "$W/u.h5" ] || { echo "FAIL: the first sweep did not finish"; exit 1; }
echo "resume guards: content, options, edited runs, missing or corrupt spec, concurrent resume all refused"
