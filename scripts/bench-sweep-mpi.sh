#!/bin/sh
# Sweep throughput on 1 and 2 MPI ranks: the same 8-coverage FEM sweep on the
# default surface sampled 32 x 32, timed end to end; the CSV tables must be identical.
# Usage: scripts/bench-sweep-mpi.sh [WETROAD] [WORKDIR]
set -eu
BIN=${1:-build/bin/wetroad}
W=${2:-build/bench-sweep-mpi}
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
MPIRUN="mpirun -np 2"
[ "$(id -u)" -eq 0 ] && MPIRUN="mpirun --allow-run-as-root -np 2"
SWEEP="sweep-coverage --scene default --size 32 --dx 9.375e-4 --coverages 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7
  --uz 1.5e-3 --ux 3e-3 --steps 2 --shear-steps 3 --tol 1e-3 -q"
now() { date +%s.%N; }
t0=$(now)
# shellcheck disable=SC2086
"$BIN" $SWEEP --out "$W/one.h5" --csv "$W/one.csv" 2>/dev/null
t1=$(now)
# shellcheck disable=SC2086
$MPIRUN "$BIN" $SWEEP --out "$W/two.h5" --csv "$W/two.csv" 2>/dev/null
t2=$(now)
cmp -s "$W/one.csv" "$W/two.csv" && same=identical || same=DIFFERENT
awk -v a="$t0" -v b="$t1" -v c="$t2" -v s="$same" 'BEGIN {
  printf "sweep throughput: 1 rank %.1f s, 2 ranks %.1f s, speedup %.2fx; results %s\n", b - a, c - b, (b - a) / (c - b), s }'
