#!/usr/bin/env bash
# photon-view under Xvfb on lavapipe, with the validation layer and synchronization validation on
# (VK_INSTANCE_LAYERS, VK_LAYER_ENABLES, and --validation, which makes any message exit 1); any
# validation message in the output fails the test too.
#   tests/viewer_test.sh <photon-view> <photon-render> <photon-image-diff> <scenes dir> <output dir>
#
# 1. 8 frames of the Cornell box in a window, screenshot of the last, against photon-render
#    --backend vulkan with the same camera and settings.
# 2. The same with the window resized after 2 frames: the last 4 frames at the new size, against
#    photon-render at that size (the resize restarts the accumulation).
# 3. --offscreen (the GPU machine's mode), 4 frames, against photon-render.
# 4. The photon-dots view runs clean and draws something; bad options exit 2.
#
# Tolerance: both programs run the same shaders on the same device with the same frame
# parameters, so the accumulated radiance is identical (queries visit every photon of a cell,
# --gather-budget 0, so the order in which atomics appended photons cannot matter). What differs
# is the tone curve: the display shader's pow() and float→UNORM conversion against libm's powf
# and lround in photon-render's PNG writer. Measured on lavapipe (Mesa 25.0.7): 1 of 90000
# channel values differs, by 1 step (RMSE 0.003). Allowed: no value off by more than 1 step and
# RMSE ≤ 0.05 (1 value in 400 off by one). A wrong exposure, channel order, sRGB curve or pixel
# mapping gives an RMSE of several steps.
set -uo pipefail
view=$1
render=$2
diff=$3
scenes=$4
out=$5
mkdir -p "$out"
failures=0

if ! command -v xvfb-run >/dev/null; then
  echo "FAIL: xvfb-run is not installed (Debian: xvfb xauth)"; exit 1
fi
export VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation
export VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT
common=("$scenes/cornell.json" --photons 20000 --seed 7 --pixel-center --gather-budget 0 --validation)

# run <name> <expected exit code> <command...>: output to $out/<name>.log; any validation message fails.
run() {
  local name=$1 code=$2
  shift 2
  local start=$SECONDS
  "$@" >"$out/$name.log" 2>&1
  local got=$?
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: $name exited $got, expected $code: $*"; tail -20 "$out/$name.log"; failures=$((failures + 1))
  elif grep -qiE "validation (error|warning)|vulkan validation|VUID-|SYNC-HAZARD" "$out/$name.log"; then
    echo "FAIL: $name printed validation messages:"; grep -iE "validation|VUID-|SYNC-" "$out/$name.log" | head -10
    failures=$((failures + 1))
  else
    echo "ok: $name ($((SECONDS - start)) s): $(tail -1 "$out/$name.log" | cut -c1-160)"
  fi
}

# same <viewer screenshot> <reference>: the tolerance above.
same() {
  if "$diff" "$1" "$2" --max-abs 1 --max-rmse 0.05 >"$out/diff.log"; then
    echo "ok: $(basename "$1") matches $(basename "$2"): $(cat "$out/diff.log")"
  else
    echo "FAIL: $(basename "$1") against $(basename "$2"): $(cat "$out/diff.log")"; failures=$((failures + 1))
  fi
}

xvfb=(xvfb-run -a -s "-screen 0 1280x800x24")

run window 0 "${xvfb[@]}" "$view" "${common[@]}" --width 200 --height 150 --frames 8 --screenshot "$out/view.png"
run window-reference 0 "$render" --backend vulkan "${common[@]}" --width 200 --height 150 --frames 8 -o "$out/view-reference.png"
same "$out/view.png" "$out/view-reference.png"

run resize 0 "${xvfb[@]}" "$view" "${common[@]}" --width 200 --height 150 --frames 6 --resize-after 2 240x180 \
  --vsync off --screenshot "$out/resized.png"
run resize-reference 0 "$render" --backend vulkan "${common[@]}" --width 240 --height 180 --frames 4 -o "$out/resized-reference.png"
same "$out/resized.png" "$out/resized-reference.png"

# --backend vulkan is the viewer's one backend (every render option of photon-render works here).
run offscreen 0 "$view" "${common[@]}" --backend vulkan --offscreen --width 160 --height 120 --frames 4 --screenshot "$out/offscreen.png"
run offscreen-reference 0 "$render" --backend vulkan "${common[@]}" --width 160 --height 120 --frames 4 -o "$out/offscreen-reference.png"
same "$out/offscreen.png" "$out/offscreen-reference.png"

run dots 0 "${xvfb[@]}" "$view" "${common[@]}" --width 200 --height 150 --frames 3 --view dots --screenshot "$out/dots.png"
# A black 200×150 PNG is under 200 bytes; the dots make it tens of kilobytes.
if [ "$(stat -c %s "$out/dots.png" 2>/dev/null || echo 0)" -lt 4000 ]; then
  echo "FAIL: the photon-dots screenshot is (nearly) empty"; failures=$((failures + 1))
fi

# --camera-path: the camera circles, the history following it (1/60 s a frame in a scripted run).
run orbit 0 "$view" "${common[@]}" --offscreen --width 160 --height 120 --frames 6 --camera-path orbit:2 \
  --screenshot "$out/orbit.png"
if cmp -s "$out/orbit.png" "$out/offscreen.png"; then
  echo "FAIL: the orbit's last frame is the still camera's"; failures=$((failures + 1))
fi
run bad-path 2 "$view" --offscreen --frames 1 --camera-path orbit:0

run no-frames 2 "$view" --offscreen
run bad-view 2 "$view" --offscreen --frames 1 --view nearest
run bad-backend 2 "$view" --offscreen --frames 1 --backend cuda
grep -qF "photon-view renders with Vulkan" "$out/bad-backend.log" || { echo "FAIL: --backend cuda says why"; failures=$((failures + 1)); }
run bad-scene 2 "$view" "$out/missing.json" --offscreen --frames 1

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"; exit 1
fi
echo "all viewer checks passed"
