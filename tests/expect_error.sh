# Sourced by the end-to-end sweep scripts: expect_error NEEDLE ARGS... runs "$BIN" ARGS and
# fails the script unless it exits with code 2 and one line on stderr containing NEEDLE.
# Needs BIN (the wetroad binary) and W (the scratch folder).
expect_error() {
  needle=$1
  shift
  set +e
  "$BIN" "$@" 2>"$W/err.txt" >/dev/null
  rc=$?
  set -e
  [ $rc -eq 2 ] || { echo "FAIL: exit $rc for: $*"; cat "$W/err.txt"; exit 1; }
  grep -q -- "$needle" "$W/err.txt" || { echo "FAIL: no '$needle' in:"; cat "$W/err.txt"; exit 1; }
  [ "$(wc -l < "$W/err.txt")" -eq 1 ] || { echo "FAIL: not one line:"; cat "$W/err.txt"; exit 1; }
}
