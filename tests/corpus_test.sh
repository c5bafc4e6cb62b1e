#!/usr/bin/env bash
# Every model file of Debian's assimp-testmodels (.obj, .gltf, .glb), rendered tiny on the CPU three
# ways: by itself (photon-render FILE), and as a mesh object of a scene file under a scene
# material, once diffuse (alone under a point light: the mesh must show) and once glass (over a
# diffuse floor). Each run must either succeed with an image that is finite and not all black, or
# be refused with exit 2 and one line that names the file (or the file of its folder that is at
# fault: a missing MTL, image or buffer is named itself, docs/scenes.md). A crash, a signal, a hang (timeout), a
# runtime failure, a NaN or a black image fails the test, and so does a nearly black one without
# the warning that says so.
#   tests/corpus_test.sh <photon-render> [--list]
# --list prints the files Photon refuses, with the reasons, as the Markdown list in docs/scenes.md.
# The corpus is $PHOTON_CORPUS (default /usr/share/assimp/models); without it the test is skipped
# (exit 77).
set -uo pipefail
render=$(realpath "$1")
list=${2:-}
corpus=${PHOTON_CORPUS:-/usr/share/assimp/models}
if [ ! -d "$corpus" ]; then
  echo "skip: no model corpus at $corpus (Debian package assimp-testmodels)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export render corpus tmp
small=(--backend cpu --width 32 --height 24 --photons 4000 --frames 1 -q)
export SMALL="${small[*]}"

# check_one <file>: writes one result line per run to $tmp/results/<n>:
#   ok <case> <file> | refused <case> <file> <message> | FAIL <case> <file> <why>
check_one() {
  local file=$1
  local rel=${file#"$corpus"/}
  local id
  id=$(printf '%s' "$rel" | tr '/ ' '__')
  local dir=$tmp/work/$id
  mkdir -p "$dir"
  local out=$tmp/results/$id
  : >"$out"
  local name
  name=$(basename "$file")

  # run <case> <args...>: one render, judged.
  run() {
    local case=$1
    shift
    # shellcheck disable=SC2086
    timeout 60 "$render" "$@" $SMALL -o "$dir/$case.pfm" --stats "$dir/$case.json" >"$dir/$case.out" 2>"$dir/$case.err"
    local code=$?
    local lines
    lines=$(wc -l <"$dir/$case.err")
    if [ "$code" -eq 0 ]; then
      local why
      if why=$(python3 - "$dir/$case.pfm" "$dir/$case.json" 2>&1 <<'EOF'
import array, json, math, sys
data = open(sys.argv[1], 'rb').read()
kind, size, scale, pixels = data.split(b'\n', 3)
values = array.array('f'); values.frombytes(pixels)
if not values or not all(math.isfinite(v) for v in values):
    sys.exit('a value that is not finite')
if not any(v > 0.0 for v in values):
    sys.exit('the image is all black')
# Nearly black (fewer than 10% of pixels at 1% of white, core/image/image.h): only with the
# warning that says so.
pixels = [values[i:i + 3] for i in range(0, len(values), 3)]
lit = sum(1 for p in pixels if max(p) >= 0.01) / len(pixels)
if lit < 0.1 and not any('nearly black' in w for w in json.load(open(sys.argv[2])).get('warnings', [])):
    sys.exit('nearly black (%.1f%% of pixels show) without a warning' % (100 * lit))
EOF
      ); then
        echo "ok $case $rel" >>"$out"
      else
        echo "FAIL $case $rel $why" >>"$out"
      fi
    elif [ "$code" -eq 2 ] && [ "$lines" -eq 1 ] && { grep -qF -- "$name" "$dir/$case.err" ||
                                                      grep -qF -- "$(dirname "$file")/" "$dir/$case.err"; }; then
      echo "refused $case $rel $(cat "$dir/$case.err")" >>"$out"
    elif [ "$code" -eq 124 ]; then
      echo "FAIL $case $rel timed out after 60 s" >>"$out"
    else
      echo "FAIL $case $rel exit $code, $lines lines: $(head -c 300 "$dir/$case.err" | tr '\n' ' ')" >>"$out"
    fi
    return "$code"
  }

  run direct "$file"
  # The scenes frame the model's bounds as the direct render measured them (the unit cube if it
  # was refused: the scene must then be refused for the same file).
  python3 - "$file" "$dir/direct.json" "$dir" <<'EOF'
import json, math, sys
path, stats, folder = sys.argv[1:]
lo, hi = [-1.0] * 3, [1.0] * 3
try:
    bounds = json.load(open(stats))['scene_stats']['bounds']
    if all(math.isfinite(v) for v in bounds['min'] + bounds['max']):
        lo, hi = bounds['min'], bounds['max']
except (OSError, KeyError, ValueError):
    pass
centre = [(a + b) / 2 for a, b in zip(lo, hi)]
radius = max(0.5 * math.dist(lo, hi), 1e-6)
distance = radius / math.sin(math.radians(20)) * 1.05
direction = [0.35, 0.3, 1.0]
norm = math.sqrt(sum(d * d for d in direction))
eye = [c + d / norm * distance for c, d in zip(centre, direction)]
# At the camera, a little behind it: it lights whatever side of a flat model the camera sees.
light = [e + 0.1 * radius * d / norm for e, d in zip(eye, direction)]
power = 4 * math.pi * distance * distance * 2.0
base = {
    'camera': {'position': eye, 'look_at': centre, 'up': [0, 1, 0], 'fov': 40},
    'materials': {'grey': {'type': 'diffuse', 'albedo': [0.8, 0.8, 0.8]}, 'glass': {'type': 'glass', 'ior': 1.5}},
    'lights': [{'type': 'point', 'position': light, 'power': [power] * 3}],
}
diffuse = dict(base, objects=[{'type': 'mesh', 'file': path, 'material': 'grey'}])
glass = dict(base, objects=[{'type': 'mesh', 'file': path, 'material': 'glass'},
                            {'type': 'plane', 'point': [0, lo[1], 0], 'normal': [0, 1, 0], 'material': 'grey'}])
json.dump(diffuse, open(folder + '/diffuse-scene.json', 'w'))
json.dump(glass, open(folder + '/glass-scene.json', 'w'))
EOF
  run diffuse "$dir/diffuse-scene.json"
  run glass "$dir/glass-scene.json"
}
export -f check_one

mkdir -p "$tmp/results" "$tmp/work"
find "$corpus" -type f \( -iname '*.obj' -o -iname '*.gltf' -o -iname '*.glb' \) -print0 | sort -z >"$tmp/files"
count=$(tr -cd '\0' <"$tmp/files" | wc -c)
xargs -0 -P 2 -n 1 bash -c 'check_one "$1"' _ <"$tmp/files"
cat "$tmp"/results/* | sort -k3,3 -k2,2 >"$tmp/all"
[ -n "${PHOTON_CORPUS_LOG:-}" ] && cp "$tmp/all" "$PHOTON_CORPUS_LOG"

if [ "$list" = "--list" ]; then
  # One entry per refused file: the reason of its direct render (the scene runs say the same
  # behind the scene's pointer), the file relative to the corpus.
  grep '^refused direct ' "$tmp/all" | while read -r _ _ rel message; do
    reason=${message#photon-render: }
    reason=${reason#"$corpus/$rel: "}
    reason=${reason//"$corpus/"/}
    echo "- \`$rel\`: $reason"
  done
  exit 0
fi

failures=$(grep -c '^FAIL ' "$tmp/all")
grep '^FAIL ' "$tmp/all"
echo "$count files: $(grep -c '^ok ' "$tmp/all") renders ok, $(grep -c '^refused ' "$tmp/all") refused with a reason, $failures failed"
[ "$failures" -eq 0 ]
