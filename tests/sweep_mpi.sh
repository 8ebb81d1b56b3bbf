#!/bin/sh
# identity: a coverage sweep on 2 MPI ranks gives results identical to 1 process
# (the CSV table, 17 digits, byte for byte). The throughput is measured by hand (README).
# Usage: sweep_mpi.sh WETROAD MPIEXEC WORKDIR
# shellcheck source=tests/mpi-test-env.sh
. "$(dirname "$0")/mpi-test-env.sh"
SWEEP="sweep-coverage --scene default --size 16 --dx 1.875e-3 --coverages 0 0.3 0.6 --realizations 2
  --uz 3e-3 --ux 1.5e-3 --steps 2 --shear-steps 2 -q"
# shellcheck disable=SC2086
"$BIN" $SWEEP --out "$W/one.h5" --csv "$W/one.csv"
# shellcheck disable=SC2086
on_two_ranks $SWEEP --out "$W/two.h5" --csv "$W/two.csv"
grep -q '"rank": 1' "$W"/two.h5.runs/run-*.json || { echo "FAIL: rank 1 did no run"; exit 1; }
cmp "$W/one.csv" "$W/two.csv" || { echo "FAIL: 2 ranks differ from 1"; diff "$W/one.csv" "$W/two.csv"; exit 1; }
echo "2 ranks identical to 1"
