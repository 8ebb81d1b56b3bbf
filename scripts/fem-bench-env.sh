# shellcheck shell=sh
# Sourced by the FEM benchmark scripts: one FEM process per core on 2 ranks (mpirun, which
# needs --allow-run-as-root as root), and the thesis-scale dataset-A surface (300 x 300,
# dx 0.1 mm, h0 0.305 mm, H 0.7, q0 = 5 qL, seed 1), made once per work directory.
export OMP_NUM_THREADS=1
MPILAUNCH="mpirun"
[ "$(id -u)" -eq 0 ] && MPILAUNCH="mpirun --allow-run-as-root"
MPIRUN="$MPILAUNCH -np 2"
export MPILAUNCH MPIRUN  # used by the scripts that source this (MPILAUNCH: without a rank count)
# dataset_a_surface WETROAD WORKDIR: writes WORKDIR/A_3.05e-4.h5 unless it is there.
dataset_a_surface() {
  [ -f "$2/A_3.05e-4.h5" ] ||
    "$1" synth --size 300 --dx 1e-4 --h0 3.05e-4 --hurst 0.7 --q0-ratio 5 --seed 1 -o "$2/A_3.05e-4.h5" -q
}
