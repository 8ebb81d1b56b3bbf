#!/bin/sh
# identity: a coverage sweep on 2 MPI ranks gives results identical to 1 process
# (the CSV table, 17 digits, byte for byte). The throughput is measured by hand (README).
# Progress: with --progress 0 every run's load steps are reported as they end, numbered, with
# their loads (mu only for the shear steps); with -q nothing is.
# Usage: sweep_mpi.sh WETROAD MPIEXEC WORKDIR
# shellcheck source=tests/mpi-test-env.sh
. "$(dirname "$0")/mpi-test-env.sh"
SWEEP="sweep-coverage --scene default --size 16 --dx 1.875e-3 --coverages 0 0.3 0.6 --realizations 2
  --uz 3e-3 --ux 1.5e-3 --steps 2 --shear-steps 2"
# shellcheck disable=SC2086
"$BIN" $SWEEP --progress 0 --out "$W/one.h5" --csv "$W/one.csv" 2> "$W/one.err" > /dev/null
# shellcheck disable=SC2086
on_two_ranks $SWEEP -q --out "$W/two.h5" --csv "$W/two.csv" 2> "$W/two.err"
for run in 1 2 3 4 5 6; do
  grep -q "run $run/6, step 2: uz 3 mm, ux 0 mm, A/A0 " "$W/one.err" &&
    grep -q "run $run/6, step 4: uz 3 mm, ux 1.5 mm, mu " "$W/one.err" ||
    { echo "FAIL: run $run's steps not reported"; cat "$W/one.err"; exit 1; }
done
[ "$(grep -c ', step [0-9]*: uz' "$W/one.err")" -eq 24 ] || { echo "FAIL: not 6 x 4 step lines"; cat "$W/one.err"; exit 1; }
! grep -q ', step ' "$W/two.err" || { echo "FAIL: -q printed step lines"; cat "$W/two.err"; exit 1; }
grep -q '"rank": 1' "$W"/two.h5.runs/run-*.json || { echo "FAIL: rank 1 did no run"; exit 1; }
cmp "$W/one.csv" "$W/two.csv" || { echo "FAIL: 2 ranks differ from 1"; diff "$W/one.csv" "$W/two.csv"; exit 1; }
echo "2 ranks identical to 1"
