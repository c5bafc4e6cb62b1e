#!/usr/bin/env bash
# Hostile input, from the outside (issue 8): every case is a clean error (one line naming the file
# or option, exit 2 for bad input, 1 for a runtime failure) or a correct image; never a crash, a
# hang, a NaN image or a half-written file.
#   tests/reliability_test.sh <photon-render> <photon-bench> <scenes dir> <photon-make-mesh>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
render=$1
bench=$2
scenes=$3
make_mesh=$4
tmp=$(mktemp -d)
cleanup() {
  mountpoint -q "$tmp/full" 2>/dev/null && umount "$tmp/full"
  rm -rf "$tmp"
}
trap cleanup EXIT
small=(--backend cpu --width 32 --height 24 --photons 5000 --frames 1 -q)

# expect <code> <stderr substring or ""> <command...>: the exit code, one line on stderr naming
# the program, and the substring.
expect() {
  local code=$1 message=$2
  shift 2
  timeout 60 "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  local lines
  lines=$(wc -l <"$tmp/err")
  if [ "$got" -ne "$code" ]; then
    fail "$* exited $got, expected $code"; cat "$tmp/err"
  elif [ "$code" -ne 0 ] && [ "$lines" -ne 1 ]; then
    fail "$*: $lines lines on stderr, expected one"; cat "$tmp/err"
  elif [ "$code" -ne 0 ] && ! grep -qE '^photon-(render|bench|make-mesh): ' "$tmp/err"; then
    fail "$*: the message does not name the program"; cat "$tmp/err"
  elif [ -n "$message" ] && ! grep -qF -- "$message" "$tmp/err"; then
    fail "$*: stderr lacks '$message'"; cat "$tmp/err"
  else
    echo "ok: exit $got: $*"
  fi
}

# 1. Inputs that crashed the bounded grid.
expect 2 "--radius" "$render" "${small[@]}" --grid bounded --radius 1e39 -o "$tmp/a.png"
# A given radius wider than the bounded grid reaches needs wider cells: fewer of them (the message
# said to raise the resolution); an automatic one is clamped to what the grid reaches.
expect 2 "lower --grid-resolution" "$render" "${small[@]}" --grid bounded --grid-resolution 256 --radius 0.5 --frames 3 -o "$tmp/a.png"
expect 0 "" "$render" "${small[@]}" --grid bounded --grid-resolution 256 --frames 3 -o "$tmp/a.png"
expect 2 "--alpha" "$render" "${small[@]}" --grid bounded --alpha nan --estimator progressive --frames 3 -o "$tmp/a.png"
python3 - "$scenes/cornell.json" "$tmp/far.json" <<'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene['materials']['grey'] = {'type': 'diffuse', 'albedo': [0.5, 0.5, 0.5]}
scene['objects'].append({'type': 'sphere', 'center': [1e20, 0, 0], 'radius': 0.1, 'material': 'grey'})
json.dump(scene, open(sys.argv[2], 'w'))
EOF
expect 0 "" "$render" "$tmp/far.json" "${small[@]}" --grid bounded -o "$tmp/far.pfm"
finite_pfm "$tmp/far.pfm" || fail "the far-sphere render is not finite"

# 2. More memory than the process may have: refused before work, not a crash.
expect 2 "lower the photons" bash -c "ulimit -v 2000000; exec \"$render\" --backend cpu --photons 50000000 --width 64 --height 48 -q -o \"$tmp/m.png\""
# The images read back count too: at 2000x2000 the CPU's buffers (825 MiB) fit under 1.4 GB, the
# auxiliary images' readback (580 MiB more) does not (issue 57: a bare "out of memory" after 6 s).
expect 2 "auxiliary images need" bash -c "ulimit -v 1400000; exec \"$render\" --backend cpu --photons 5000 --frames 1 --width 2000 --height 2000 --aov --denoise off -q -o \"$tmp/m.exr\""

# 3. Outputs appear whole or not at all.
ln -s /dev/full "$tmp/full.png"
expect 2 "character device" "$render" "${small[@]}" -o "$tmp/full.png"
[ -L "$tmp/full.png" ] || fail "the link to /dev/full was replaced"
expect 2 "character device" "$render" "${small[@]}" -o "$tmp/ok.png" --stats "$tmp/full.png"
[ -e "$tmp/ok.png" ] && fail "an image was written although the stats could not be"
expect 1 "File too large" bash -c "ulimit -f 1; exec \"$render\" --backend cpu --width 64 --height 64 --photons 5000 -q -o \"$tmp/big.pfm\""
[ -e "$tmp/big.pfm" ] && fail "a truncated big.pfm was left"
ls -A "$tmp" | grep -q '^\.big' && fail "a temporary file was left"
mkdir "$tmp/full"
if mount -t tmpfs -o size=16k tmpfs "$tmp/full" 2>/dev/null; then
  for f in x.png x.pfm x.exr; do
    expect 1 "No space left on device" "$render" "${small[@]}" --width 200 --height 200 -o "$tmp/full/$f"
  done
  [ -z "$(ls -A "$tmp/full")" ] || { fail "files were left on the full disk"; ls -la "$tmp/full"; }
  dd if=/dev/zero of="$tmp/full/filler" bs=1k 2>/dev/null
  expect 1 "No space left on device" "$render" "${small[@]}" -o "$tmp/ok.pfm" --stats "$tmp/full/s.json"
  [ "$(ls -A "$tmp/full")" = filler ] || { fail "files were left on the full disk"; ls -la "$tmp/full"; }
else
  echo "skip: no tmpfs mount here (the ulimit -f case covers a failing write)"
fi

# 4. Values the scene loader refused, refused on the command line too.
for option in "--radius 1e-45" "--alpha nan" "--cell-size nan" "--radius nan" "--exposure nan" "--exposure inf" \
              "--caustic-radius -inf" "--photons 1.5"; do
  # shellcheck disable=SC2086
  expect 2 "${option%% *}" "$render" "${small[@]}" $option -o "$tmp/a.png"
done
expect 2 "omit it" "$render" "${small[@]}" --radius 0 -o "$tmp/a.png"
[ "$(wc -c <"$tmp/err")" -lt 200 ] || fail "--radius 0: a message of $(wc -c <"$tmp/err") bytes"

# 4b. No accepted value hangs a render (issue 16): each is refused with one line naming the option,
#     or a 64x48 render (sppm over 3 frames, where the cells follow the radii of the frame before)
#     finishes with a finite image. --radius 1e12 once took 100 s here and 1e15 never ended (the
#     sppm cells followed the radius histogram, whose bins end at 2^32); --time nan rendered forever.
judge() {
  local option=$1 got=$2
  if [ "$got" -eq 2 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -qF -- "${option%% *}" "$tmp/err"; then
    echo "ok: refused: $option: $(cat "$tmp/err")"
  elif [ "$got" -eq 0 ] && finite_pfm "$tmp/h.pfm"; then
    echo "ok: rendered: $option"
  else
    fail "$option: exit $got (124: the 60 s timeout)"; cat "$tmp/err"
  fi
}
for option in "--time nan" "--time inf" "--time -1" "--time 1e400" "--radius nan" "--radius 1e12" "--radius 1e15" \
              "--radius 1e-15" "--caustic-radius 1e15" "--caustic-radius 1e-15" "--caustic-radius nan" \
              "--alpha nan" "--cell-size 64" "--frames nan" "--photons inf" "--k nan" "--exposure 1e400"; do
  for estimator in sppm radius knn progressive cell; do
    rm -f "$tmp/h.pfm"
    # shellcheck disable=SC2086
    timeout 60 "$render" --backend cpu --width 64 --height 48 --photons 20000 --frames 3 --estimator "$estimator" \
      $option -q -o "$tmp/h.pfm" >"$tmp/out" 2>"$tmp/err"
    judge "$option ($estimator)" $?
  done
done
# knn visited every photon within its radius: with one as wide as the scene (or so small that all
# photons share the grid's clamped border cells) a 640x480 frame of 1M photons took 2 minutes (now seconds).
for option in "--radius 1e15" "--radius 1e-15"; do
  rm -f "$tmp/h.pfm"
  # shellcheck disable=SC2086
  timeout 60 "$render" --backend cpu --width 640 --height 480 --photons 1000000 --frames 1 --estimator knn $option -q \
    -o "$tmp/h.pfm" >"$tmp/out" 2>"$tmp/err"
  judge "$option (knn, 1M photons)" $?
done

# 5. No hangs: device files and FIFOs are refused at once.
expect 2 "character device" "$render" /dev/zero "${small[@]}" -o "$tmp/a.png"
expect 2 "character device" "$render" /dev/urandom "${small[@]}" -o "$tmp/a.png"
mkfifo "$tmp/fifo"
expect 2 "FIFO" "$render" "$tmp/fifo" "${small[@]}" -o "$tmp/a.png"
head -c 300000000 /dev/zero | tr '\0' ' ' >"$tmp/huge.json"
expect 2 "larger than the 256 MiB" "$render" "$tmp/huge.json" "${small[@]}" -o "$tmp/a.png"
rm -f "$tmp/huge.json"

# 6. An output that cannot be written fails before the render (a million frames would time out).
expect 2 "no/such/dir" "$render" "${small[@]}" --frames 1000000 -o "$tmp/no/such/dir/x.png"

# 7. The same seed twice gives the same image, bit for bit: on the CPU always, on a Vulkan device
#    (lavapipe here) by default, and with --deterministic (the last of a flag's forms counts).
for run in cpu vulkan "vulkan --no-deterministic --deterministic"; do
  read -r backend flags <<<"$run"
  read -ra extra <<<"$flags"
  if "$render" --backend "$backend" --width 40 --height 30 --photons 20000 --frames 2 "${extra[@]}" -q -o "$tmp/r1.pfm" 2>/dev/null; then
    "$render" --backend "$backend" --width 40 --height 30 --photons 20000 --frames 2 "${extra[@]}" -q -o "$tmp/r2.pfm"
    cmp -s "$tmp/r1.pfm" "$tmp/r2.pfm" && echo "ok: $backend ${extra[*]}: the same seed twice, the same image" ||
      fail "$backend ${extra[*]}: the same seed twice gave different images"
  else
    echo "skip: no $backend backend here"
  fi
done

# 8. photon-bench checks its numbers and its outputs before measuring.
for photons in -1 4294967296 0; do
  expect 2 "--photons" "$bench" --backends cpu --resolutions 32x24 --photons "$photons" --cpu-frames 1
done
expect 2 "no/such" "$bench" --backends cpu --resolutions 32x24 --photons 1000 --json "$tmp/no/such/b.json"
expect 2 "character device" "$bench" --backends cpu --resolutions 32x24 --photons 1000 --csv /dev/full
expect 2 "--vary" "$bench" --backends cpu --resolutions 32x24 --photons 1000 --vary radius=nan
# A resolution is WIDTHxHEIGHT and nothing more (64x48x2 was taken as 64x48).
for size in 64x48x2 64x48x 64x 64x48junk; do
  expect 2 "--resolutions: '$size' is not WIDTHxHEIGHT" "$bench" --backends cpu --resolutions "$size" --photons 1000 --cpu-frames 1
done

# 9. photon-make-mesh: a --material that is not a JSON object is bad input (exit 2), not a failure.
expect 2 "--material: line 1" "$make_mesh" --triangles 100 --material '{"pbr": ' -o "$tmp/m.glb"
expect 2 "--material: must be a JSON object" "$make_mesh" --triangles 100 --material '[1, 2]' -o "$tmp/m.glb"
[ -e "$tmp/m.glb" ] && fail "photon-make-mesh wrote a mesh for a bad --material"

# 10. Model files: no token quoted whole, no image size taken on trust.
printf '{"camera": {"position": [0, 1, 4], "look_at": [0, 1, 0]}, "background": [%s, 0, 0], "materials": {}, "lights": [], "objects": []}' \
  "$(head -c 100000 /dev/zero | tr '\0' 7)" >"$tmp/long.json"
expect 2 "long.json: " "$render" "$tmp/long.json" "${small[@]}" -o "$tmp/a.png"
[ "$(wc -c <"$tmp/err")" -lt 200 ] || fail "a 100000-digit number: a message of $(wc -c <"$tmp/err") bytes"
{ printf 'v '; head -c 100000 /dev/zero | tr '\0' 9; printf ' 0 0\n'; } >"$tmp/long.obj"
expect 2 "long.obj: line 1: " "$render" "$tmp/long.obj" "${small[@]}" -o "$tmp/a.png"
[ "$(wc -c <"$tmp/err")" -lt 200 ] || fail "a 100000-digit OBJ number: a message of $(wc -c <"$tmp/err") bytes"
# A valid PNG header announcing 100000 x 100000 texels (stb_image said "unknown image type").
python3 - "$tmp" <<'PNG'
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 100000, 100000, 8, 2, 0, 0, 0))
png += chunk(b'IDAT', zlib.compress(b'\0' * 301)) + chunk(b'IEND', b'')
open(sys.argv[1] + '/huge.png', 'wb').write(png)
open(sys.argv[1] + '/huge.mtl', 'w').write('newmtl t\nmap_Kd huge.png\n')
open(sys.argv[1] + '/huge.obj', 'w').write('mtllib huge.mtl\nusemtl t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n')
PNG
expect 2 "huge.png: image of 100000x100000 texels; at most 8192 a side" "$render" "$tmp/huge.obj" "${small[@]}" -o "$tmp/a.png"

# 11. Smaller things.
expect 2 "scene: an empty file name" "$render" "" "${small[@]}" -o "$tmp/a.png"
{ cat "$scenes/cornell.json"; printf '\0'; } >"$tmp/nul.json"
expect 2 "NUL" "$render" "$tmp/nul.json" "${small[@]}" -o "$tmp/a.png"
sed 's/"material": "mirror"/"material": "\xc2\x85mirror\\u001b[2J"/' "$scenes/cornell.json" >"$tmp/bytes.json"
expect 2 '\xc2\x85mirror\x1b[2J' "$render" "$tmp/bytes.json" "${small[@]}" -o "$tmp/a.png"
LC_ALL=C grep -q $'[\x80-\xff\x1b]' "$tmp/err" && fail "raw bytes of the file reached stderr"
printf '\xff\xc2\x85{' >"$tmp/bytes.json"
expect 2 "\\xff" "$render" "$tmp/bytes.json" "${small[@]}" -o "$tmp/a.png"
LC_ALL=C grep -q $'[\x80-\xff]' "$tmp/err" && fail "raw bytes of the file reached stderr"
expect 2 "--width" "$render" "${small[@]}" --width 0 -o "$tmp/a.png"
expect 2 "not expected" "$render" "${small[@]}" --no-such-option
expect 2 "CPU backend has no devices" "$render" "${small[@]}" --device 0 -o "$tmp/a.png"
if command -v script >/dev/null 2>&1; then
  # On a terminal 40 columns wide: -q prints nothing; otherwise the bar never wraps (one line).
  script -qec "stty cols 40; $render ${small[*]} --frames 30 -o $tmp/t.png" /dev/null >"$tmp/tty.txt"
  [ -s "$tmp/tty.txt" ] && fail "-q printed on the terminal: $(cat -v "$tmp/tty.txt" | head -c 200)"
  small_loud=(--backend cpu --width 32 --height 24 --photons 5000)
  script -qec "stty cols 40; $render ${small_loud[*]} --frames 30 -o $tmp/t.png" /dev/null >"$tmp/tty.txt"
  python3 - "$tmp/tty.txt" <<'EOF' || fail "the progress bar is wider than the terminal or breaks lines"
import re, sys
text = open(sys.argv[1], 'rb').read().decode('utf-8', 'replace')
bar = text.split('\n')[0]
updates = [re.sub(r'\x1b\[K', '', u) for u in bar.split('\r') if u]
sys.exit(0 if updates and all(len(u) < 40 for u in updates) else 1)
EOF
else
  echo "skip: no script(1) for a terminal"
fi

[ "$failures" -eq 0 ] && echo "all reliability checks passed"
exit "$failures"
