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
# Processes that disagree are refused before any frame, each naming what differs (issue 57).
small=(--backend cpu --width 32 --height 24 --photons 5000 --frames 2 -q)
check_refused() {  # <what the line must name> <mpirun's argument list...>
  local want=$1; shift
  cd "$tmp" && timeout 120 "$mpirun" --bind-to none "$@" > "$tmp/refused.log" 2>&1
  local code=$?
  [ "$code" -eq 2 ] || fail "processes that disagree ($want) exited $code, not 2"
  grep -q -- "$want" "$tmp/refused.log" && echo "ok: refused, naming $want" || { fail "the refusal does not name $want"; cat "$tmp/refused.log"; }
}
check_refused "the scene's" -np 1 "$render" "$scenes/cornell.json" "${small[@]}" -o "$tmp/d.pfm" : -np 1 "$render" "$scenes/caustic.json" "${small[@]}" -o "$tmp/d.pfm"
check_refused "--seed differs" -np 1 "$render" "$scenes/cornell.json" "${small[@]}" -o "$tmp/d.pfm" : -np 1 "$render" "$scenes/cornell.json" "${small[@]}" --seed 9 -o "$tmp/d.pfm"
check_refused "--frames differs" -np 1 "$render" "$scenes/cornell.json" "${small[@]}" -o "$tmp/d.pfm" : -np 1 "$render" "$scenes/cornell.json" "${small[@]}" --frames 3 -o "$tmp/d.pfm"
# A signal to a process other than the first stops every process after the same frame; the
# first writes the image so far and all exit 128 + the signal.
for sig in TERM INT; do
  rm -f "$tmp/signalled.pfm"
  cd "$tmp" && timeout 120 "$mpirun" --bind-to none -np 2 "$render" "$scenes/cornell.json" --backend cpu --width 32 --height 24 \
    --photons 5000 --frames 1000000 -o "$tmp/signalled.pfm" > "$tmp/signal.log" 2>&1 &
  launcher=$!
  second=""
  for _ in $(seq 100); do  # the process of rank 1, once it runs
    for pid in $(pgrep -f -- "^$render .*signalled.pfm"); do
      tr '\0' '\n' < "/proc/$pid/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1" && second=$pid
    done
    [ -n "$second" ] && break
    sleep 0.1
  done
  sleep 1
  kill -"$sig" "$second"
  wait "$launcher"
  code=$?
  want=$([ "$sig" = TERM ] && echo 143 || echo 130)
  [ "$code" -eq "$want" ] && echo "ok: SIG$sig to the second process: mpirun exited $code" \
    || { fail "SIG$sig to the second process: mpirun exited $code, not $want"; cat "$tmp/signal.log"; }
  [ -s "$tmp/signalled.pfm" ] || fail "SIG$sig to the second process: no image so far"
  grep -q "in another process" "$tmp/signal.log" || fail "SIG$sig: the first process did not say another stopped it"
done
[ "$failures" -eq 0 ] && echo "all MPI checks passed"
exit "$failures"
