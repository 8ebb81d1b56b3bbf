#!/bin/sh
# Installs the Debian packages wetroad builds against (and librsvg2-bin, libxml2-utils for the
# test that renders the report), only those that are missing.
# Non-interactive; uses sudo when not root. Safe to run repeatedly.
# --fuzz: the fuzzing tool chain instead (clang and its libFuzzer runtime; make fuzz).
set -eu
PACKAGES="cmake g++ make pkg-config libfftw3-dev libhdf5-openmpi-dev libopenmpi-dev openmpi-bin \
libcli11-dev nlohmann-json3-dev libssl-dev libeigen3-dev libgtest-dev petsc-dev libsuitesparse-dev libzip-dev libpugixml-dev libcgal-dev gnuplot-nox librsvg2-bin libxml2-utils chromium-headless-shell"
[ "${1:-}" = "--fuzz" ] && PACKAGES="clang libclang-rt-14-dev"

missing=""
for p in $PACKAGES; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0

echo "wetroad: installing missing Debian packages:$missing"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "wetroad: error: need root or sudo to install:$missing" >&2; exit 2; fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing
