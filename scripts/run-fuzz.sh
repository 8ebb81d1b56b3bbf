#!/bin/sh
# Runs one libFuzzer target for a fixed time from its seeds (make fuzz) and prints how many
# inputs it tried. A finding (crash, hang > 10 s, sanitizer report, an exception other than
# InputError) stops it with exit 1 and leaves the input as FUZZ_DIR/artifacts/<target>-crash-*.
# Usage: run-fuzz.sh TARGET_BINARY SEED_DIR CORPUS_DIR SECONDS [extra libFuzzer flags...]
set -eu
BIN=$1
SEEDS=$2
CORPUS=$3
SECONDS_=$4
shift 4
name=$(basename "$BIN")
ART=$(dirname "$CORPUS")/../artifacts
mkdir -p "$CORPUS" "$ART"
LOG=$(dirname "$CORPUS")/$name.log
echo "fuzz $name for ${SECONDS_} s (seeds $SEEDS, corpus $CORPUS)"
set +e
# A corrupt HDF5 header can make libhdf5 ask for hundreds of GB: glibc then returns NULL and
# libhdf5 reports an error (the command line says "corrupt file"); ASan is told to do the same
# above 4 GB (allocator_may_return_null, max_allocation_size_mb: shadowing such a block costs
# ASan minutes) instead of calling it a finding, and libFuzzer's own malloc limit
# is lifted above it. wetroad's own allocations are checked against memory before they are made.
# FUZZ_ASAN_EXTRA adds ASan options (make fuzz passes a small quarantine for fuzz_height_map:
# libhdf5 callocs megabytes per file opened, and fresh pages for each cost it half its speed).
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1:max_allocation_size_mb=4096${FUZZ_ASAN_EXTRA:+:$FUZZ_ASAN_EXTRA}:suppressions=$(dirname "$0")/../tests/sanitizers/asan.supp UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
LSAN_OPTIONS=suppressions=$(dirname "$0")/../tests/sanitizers/lsan.supp:print_suppressions=0 \
OMPI_MCA_memory=^patcher OMPI_MCA_mca_base_component_disable_dlclose=1 \
  "$BIN" "$CORPUS" "$SEEDS" -max_total_time="$SECONDS_" -timeout=10 -rss_limit_mb=4096 -malloc_limit_mb=1000000 -print_final_stats=1 \
  -artifact_prefix="$ART/$name-" "$@" >"$LOG" 2>&1
rc=$?
set -e
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$LOG" | grep -o '[0-9]*$' | tail -1 || echo "?")
if [ $rc -ne 0 ]; then
  echo "  FINDING after $runs inputs (exit $rc); log $LOG:"
  grep -E "ERROR|runtime error|terminate|Exception|SUMMARY|Test unit written" "$LOG" | head -20
  exit 1
fi
echo "  $runs inputs, no finding ($(grep -o 'cov: [0-9]*' "$LOG" | tail -1), log $LOG)"
