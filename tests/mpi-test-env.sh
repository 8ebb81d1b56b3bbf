# shellcheck shell=sh
# Sourced by the command-line tests that compare 1 and 2 MPI ranks (sweep_mpi.sh,
# contact_mpi.sh): their arguments are WETROAD MPIEXEC WORKDIR.
# Sets BIN, MPIEXEC and W (made afresh) and one thread per rank; on_two_ranks CMD... runs
# wetroad CMD on 2 ranks (root allowed: CI runs as root; oversubscribed: CI may have 1 core).
set -eu
BIN=$1
MPIEXEC=$2
W=$3
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
on_two_ranks() { "$MPIEXEC" --allow-run-as-root --oversubscribe -np 2 "$BIN" "$@"; }
