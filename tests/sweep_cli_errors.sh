#!/bin/sh
# Sweep commands refuse bad input with a one-line error naming the option or file, exit code 2,
# and no output file: unknown dataset, surface file and synthesis options together, a coverage
# list out of order, a contact-model option (--progress) with the hysteresis model or negative,
# and --resume with parameters different from the checkpointed sweep's.
# Usage: sweep_cli_errors.sh WETROAD WORKDIR
set -eu
BIN=$1
W=$2
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
. "$(dirname "$0")/expect_error.sh"
expect_error "--dataset" sweep-roughness --dataset Z --uz 1e-3 --ux 1e-3 --out "$W/r.h5"
expect_error "--surface" sweep-coverage --surface x.h5 --scene default --uz 1e-3 --ux 1e-3 --out "$W/c.h5"
expect_error "--coverages" sweep-coverage --scene default --size 16 --coverages 0.4 0.2 --uz 1e-3 --ux 1e-3 --out "$W/c.h5"
expect_error "--model" sweep-coverage --scene default --size 16 --model analytic --uz 1e-3 --ux 1e-3 --out "$W/c.h5"
expect_error "--progress" sweep-coverage --scene default --size 16 --model hysteresis --progress 0 --out "$W/c.h5"
expect_error "--progress" sweep-coverage --scene default --size 16 --progress -1 --uz 1e-3 --ux 1e-3 --out "$W/c.h5"
[ ! -e "$W/c.h5" ] && [ ! -e "$W/r.h5" ] || { echo "FAIL: output written after an error"; exit 1; }
"$BIN" sweep-coverage --scene default --size 16 --dx 1.875e-3 --coverages 0 --uz 1e-3 --ux 1e-3 --steps 1 \
  --shear-steps 1 --out "$W/c.h5" -q
expect_error "different sweep parameters" sweep-coverage --scene default --size 16 --dx 1.875e-3 --coverages 0 \
  --uz 2e-3 --ux 1e-3 --steps 1 --shear-steps 1 --out "$W/c.h5" --resume
echo "sweep errors: clear, one line, exit 2, no output"
