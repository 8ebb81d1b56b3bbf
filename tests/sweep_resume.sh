#!/bin/sh
# a coverage sweep killed with SIGKILL after at least two finished runs resumes
# (--resume), redoes at most the run in progress, and ends with results identical to an
# uninterrupted sweep (the CSV table, written to 17 digits, compared byte for byte).
# Usage: sweep_resume.sh WETROAD WORKDIR
set -eu
BIN=$1
W=$2
rm -rf "$W" && mkdir -p "$W"
export OMP_NUM_THREADS=1
SWEEP="sweep-coverage --scene default --size 16 --dx 1.875e-3 --coverages 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7
  --uz 3e-3 --ux 1.5e-3 --steps 2 --shear-steps 2 -q"

# shellcheck disable=SC2086
"$BIN" $SWEEP --out "$W/whole.h5" --csv "$W/whole.csv"

# shellcheck disable=SC2086
"$BIN" $SWEEP --out "$W/cut.h5" --csv "$W/cut.csv" &
pid=$!
i=0
while [ "$(ls "$W/cut.h5.runs" 2>/dev/null | grep -c '^run-')" -lt 2 ]; do
  i=$((i + 1))
  [ $i -gt 600 ] && { echo "no two finished runs within 60 s"; kill -9 $pid; exit 1; }
  sleep 0.1
done
kill -9 $pid
wait $pid 2>/dev/null || true
[ -e "$W/cut.csv" ] && { echo "FAIL: the killed sweep had already finished; nothing was resumed"; exit 1; }
before=$(ls "$W/cut.h5.runs" | grep -c '^run-')
sums_before=$(cd "$W/cut.h5.runs" && md5sum run-*.json)
echo "killed after $before finished runs"

# Without --resume, the checkpoint is protected.
# shellcheck disable=SC2086
if "$BIN" $SWEEP --out "$W/cut.h5" 2>"$W/err.txt"; then echo "FAIL: an existing checkpoint was overwritten"; exit 1; fi
grep -q -- "--resume" "$W/err.txt" || { echo "FAIL: no hint at --resume:"; cat "$W/err.txt"; exit 1; }

# shellcheck disable=SC2086
"$BIN" $SWEEP --out "$W/cut.h5" --csv "$W/cut.csv" --resume
# The runs finished before the kill were kept, not redone.
(cd "$W/cut.h5.runs" && echo "$sums_before" | md5sum -c --quiet -) || { echo "FAIL: finished runs were redone"; exit 1; }
cmp "$W/whole.csv" "$W/cut.csv" || { echo "FAIL: resumed results differ"; diff "$W/whole.csv" "$W/cut.csv"; exit 1; }
echo "resumed sweep identical to the uninterrupted one ($before runs kept)"
