#!/usr/bin/env bash
# Ctrl-C during a render, from the outside (issue 16): the first SIGINT (or SIGTERM) finishes the
# frame in flight, writes the image so far and the stats, says so on one line and exits 128 + the
# signal (130, 143); a second one ends the process at once with nothing at the output's path.
#   tests/interrupt_test.sh <photon-render>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
render=$1
tmp=$(mktemp -d)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -KILL "$pid" 2>/dev/null; done
  rm -rf "$tmp"
}
trap cleanup EXIT

# finish <pid> <seconds>: waits for the process to end (a hang is killed and fails), sets $code.
finish() {
  local pid=$1 limit=$2 waited=0
  while kill -0 "$pid" 2>/dev/null && [ "$waited" -lt "$((limit * 10))" ]; do
    sleep 0.1
    waited=$((waited + 1))
  done
  if kill -0 "$pid" 2>/dev/null; then
    fail "photon-render is still running $limit s after the signal"
    kill -KILL "$pid"
  fi
  wait "$pid"
  code=$?
}

# Time for the render to load and start its frames.
settle() { sleep 1.5; }

# 1. One signal: the frames so far are written, whole.
for signal in INT TERM; do
  expected=$((128 + $(kill -l "$signal")))
  out=$tmp/one-$signal.pfm
  "$render" --backend cpu --width 64 --height 48 --photons 20000 --time 100 -o "$out" --stats "$tmp/one-$signal.json" \
    2>"$tmp/err" &
  pid=$!
  pids+=("$pid")
  settle
  kill -"$signal" "$pid"
  finish "$pid" 30
  if [ "$code" -ne "$expected" ]; then
    fail "SIG$signal: exit $code, expected $expected"; cat "$tmp/err"
  elif [ "$(wc -l <"$tmp/err")" -ne 1 ] || ! grep -qE "^photon-render: (interrupted|terminated): stopped after [0-9]+ frames?; the image so far is in $out, the stats in" "$tmp/err"; then
    fail "SIG$signal: not the one line expected on stderr:"; cat "$tmp/err"
  elif ! finite_pfm "$out"; then
    fail "SIG$signal: the image is missing or not finite"
  elif ! python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['frames'] >= 1" "$tmp/one-$signal.json"; then
    fail "SIG$signal: the stats are missing or wrong"
  else
    echo "ok: SIG$signal: exit $code, $(cat "$tmp/err")"
  fi
  ls -A "$tmp" | grep -q '^\.one' && fail "SIG$signal: a temporary file was left"
done

# 2. Two signals: the process ends at once, in the middle of one frame that would take minutes
#    (final gathering with 1024 rays a pixel; the signals must not straddle a frame's end), and
#    nothing is written.
out=$tmp/two.pfm
"$render" --backend cpu --width 640 --height 480 --photons 100000 --estimator radius --global final-gather \
  --gather-rays 1024 --frames 1 -q -o "$out" --stats "$tmp/two.json" 2>"$tmp/err" &
pid=$!
pids+=("$pid")
settle
kill -INT "$pid"
# Apart, or the kernel merges them into one pending signal.
sleep 0.1
kill -INT "$pid"
finish "$pid" 5
if [ "$code" -ne 130 ]; then
  fail "two SIGINTs: exit $code, expected 130"; cat "$tmp/err"
elif [ -e "$out" ] || [ -e "$tmp/two.json" ]; then
  fail "two SIGINTs: an output was written"
elif ls -A "$tmp" | grep -q '^\.two'; then
  fail "two SIGINTs: a temporary file was left: $(ls -A "$tmp")"
else
  echo "ok: two SIGINTs: exit $code, no output"
fi

# 3. The second signal while the output is being written: the temporary file goes with the
#    process (core/system/output_file.h), so that a killed render leaves nothing behind. Where the second
#    signal lands varies (the frame, the write of 24 MiB of PFM, after): the image is whole or
#    absent either way.
out=$tmp/big.pfm
"$render" --backend cpu --width 2048 --height 1536 --photons 1000 --max-depth 1 --frames 1 -q -o "$out" 2>"$tmp/err" &
pid=$!
pids+=("$pid")
sleep 1
kill -INT "$pid"
sleep 0.05
kill -INT "$pid" 2>/dev/null
finish "$pid" 30
if [ "$code" -ne 130 ] && [ "$code" -ne 0 ]; then
  # 0: the render was done before the signals came (a fast machine): the checks below still hold.
  fail "two SIGINTs around the write: exit $code, expected 130 (or 0)"; cat "$tmp/err"
elif [ -e "$out" ] && ! finite_pfm "$out"; then
  fail "two SIGINTs around the write: a partial image"
elif ls -A "$tmp" | grep -q '^\.big'; then
  fail "two SIGINTs around the write: a temporary file was left"
else
  echo "ok: two SIGINTs around a write: exit $code, the image $([ -e "$out" ] && echo whole || echo absent), no temporary file"
fi

# 4. On a terminal, the progress line ends before the message, which starts a line of its own.
if command -v script >/dev/null 2>&1; then
  # --foreground: timeout signals the render only, not its whole process group as well (which
  # made two signals, and the render end at once without a message).
  script -qec "timeout --foreground -s INT 1.5 $render --backend cpu --width 64 --height 48 --photons 20000 --time 100 -o $tmp/tty.png" \
    /dev/null >"$tmp/tty.txt"
  if python3 - "$tmp/tty.txt" <<'EOF'
import sys
lines = open(sys.argv[1], 'rb').read().decode('utf-8', 'replace').split('\n')
sys.exit(0 if any(l.startswith('photon-render: interrupted: stopped after') for l in lines) else 1)
EOF
  then
    echo "ok: on a terminal, the message has a line of its own"
  else
    fail "on a terminal, the message is not on a line of its own: $(cat -v "$tmp/tty.txt" | tail -c 300)"
  fi
else
  echo "skip: no script(1) for a terminal"
fi

[ "$failures" -eq 0 ] && echo "all interrupt checks passed"
exit "$failures"
