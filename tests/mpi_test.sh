#!/usr/bin/env bash
# photon-render over MPI on this host (core/render/mpi_collective.h): two processes, and two
# processes of two CPU devices each, render one process's image bit for bit with --deterministic;
# a timed render stops after the same frame in every process; only the first writes.
#   tests/mpi_test.sh <mpirun> <photon-render> <scenes dir>
set -uo pipefail
mpirun=$1
render=$2
scenes=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Root in containers and CI, more processes than cores, and no cross-memory attach in containers.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
args=("$scenes/caustic.json" --width 64 --height 48 --photons 30001 --frames 3 --deterministic)

"$render" "${args[@]}" --backend cpu -q -o "$tmp/one.pfm" || fail "one process"
for layout in "2 cpu" "2 cpu,cpu" "3 cpu"; do
  set -- $layout
  cd "$tmp" && "$mpirun" --bind-to none -np "$1" "$render" "${args[@]}" --backend "$2" -q -o "$tmp/mpi-$1-$2.pfm" \
    --stats "$tmp/mpi-$1-$2.json" || fail "mpirun -np $1 --backend $2 exited $?"
  cmp -s "$tmp/one.pfm" "$tmp/mpi-$1-$2.pfm" && echo "ok: mpirun -np $1 --backend $2: one process's image" \
    || fail "mpirun -np $1 --backend $2 rendered another image"
  grep -q "\"processes\": *$1" "$tmp/mpi-$1-$2.json" || fail "the stats of -np $1 do not name $1 processes"
done
# Every process stops after the frame the first one stops after: the run ends, and one image.
cd "$tmp" && timeout 120 "$mpirun" --bind-to none -np 2 "$render" "${args[@]:0:7}" --backend cpu --time 0.5 -q -o "$tmp/timed.png" \
  || fail "a timed render over MPI did not end (exit $?)"
[ -s "$tmp/timed.png" ] || fail "the timed render wrote no image"
[ "$failures" -eq 0 ] && echo "all MPI checks passed"
exit "$failures"
