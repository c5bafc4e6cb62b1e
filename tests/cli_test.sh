#!/usr/bin/env bash
# photon-render from the outside: exit codes (0 ok, 2 bad input, 1 runtime failure), one-line
# messages that name the file and place, and every output format.
#   tests/cli_test.sh <photon-render> <scenes dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
render=$1
scenes=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
small=(--backend cpu --width 32 --height 24 --photons 5000 --frames 1)

# expect <code> <stderr substring or ""> <args...>
expect() {
  local code=$1 message=$2
  shift 2
  "$render" "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  if [ "$got" -ne "$code" ]; then
    fail "photon-render $* exited $got, expected $code"; cat "$tmp/err"
  elif [ -n "$message" ] && ! grep -qF -- "$message" "$tmp/err"; then
    fail "photon-render $*: stderr lacks '$message'"; cat "$tmp/err"
  else
    echo "ok: exit $got: photon-render $*"
  fi
}

# mesh_scene <model file> <camera position> <look at> <light position>: a scene file's JSON that
# shows one model, lit by a point light of power 10 (the positions as "x, y, z").
mesh_scene() {
  printf '{"camera": {"position": [%s], "look_at": [%s]}, "materials": {}, "lights": [{"type": "point", "position": [%s], "power": 10}], "objects": [{"type": "mesh", "file": "%s"}]}' "$2" "$3" "$4" "$1"
}

# Success, every format, the default scene and a file.
expect 0 "" "${small[@]}" -o "$tmp/a.png"
expect 0 "" "${small[@]}" -o "$tmp/a.exr"
expect 0 "" "${small[@]}" -o "$tmp/a.pfm" --stats "$tmp/stats.json" --frames 2 --estimator progressive
expect 0 "" "$scenes/cornell.json" "${small[@]}" -o "$tmp/b.png" --pixel-center --estimator knn --k 16
# A flag's --no- form turns off what a scene file turned on; the last form given counts.
sed 's/"render": { /"render": { "pixel_center": true, /' "$scenes/cornell.json" >"$tmp/centred.json"
expect 0 "" "$scenes/cornell.json" "${small[@]}" -o "$tmp/jittered.pfm"
expect 0 "" "$tmp/centred.json" "${small[@]}" -o "$tmp/centred.pfm"
expect 0 "" "$tmp/centred.json" "${small[@]}" -o "$tmp/off.pfm" --pixel-center --no-pixel-center
cmp -s "$tmp/jittered.pfm" "$tmp/off.pfm" && ! cmp -s "$tmp/jittered.pfm" "$tmp/centred.pfm" \
  || fail "--no-pixel-center did not undo the scene file's pixel_center"
expect 0 "" "${small[@]}" -o "$tmp/n.png" --deterministic --no-deterministic
# The denoiser: on by default, off by --denoise off; an EXR carries the raw image and the AOVs
# as layers (OpenEXR keeps channel names as text in its header).
expect 0 "" "${small[@]}" --frames 2 -o "$tmp/den.pfm"
expect 0 "" "${small[@]}" --frames 2 -o "$tmp/raw.pfm" --denoise off
! cmp -s "$tmp/den.pfm" "$tmp/raw.pfm" || fail "--denoise off changed nothing"
expect 2 "--denoise" "${small[@]}" -o "$tmp/x.png" --denoise maybe
expect 0 "" "${small[@]}" --frames 2 -o "$tmp/aov.exr" --aov
for channel in raw.R albedo.G normal.Z depth.Z variance.Y; do
  grep -qaF "$channel" "$tmp/aov.exr" || fail "--aov: no channel $channel in the EXR"
done
# A device that is not there: the list of devices on the message's one line.
"$render" "${small[@]}" --backend vulkan --device 9 -o "$tmp/x.png" 2>"$tmp/err" >/dev/null
! grep -qF 'x0a' "$tmp/err" || { fail "--device 9 printed an escaped newline:"; cat "$tmp/err"; }
expect 2 "--deterministic" "${small[@]}" -o "$tmp/n.png" --no-deterministic=maybe
for f in a.png a.exr a.pfm b.png stats.json; do
  [ -s "$tmp/$f" ] || fail "$f was not written"
done
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['frames']==2 and 'gather' in j['stages'] and j['photons']['global']['stored']>0" "$tmp/stats.json" \
  || fail "stats JSON"

# No length anywhere: about kDefaultRenderSeconds of frames, sppm; --time with --frames: the frames cap it.
expect 0 "" --backend cpu --width 32 --height 24 --photons 5000 -o "$tmp/d.png" --stats "$tmp/d.json"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['estimator']=='sppm' and j['frames']>1 and 1.9<=j['wall_seconds']<10, j" "$tmp/d.json" \
  || fail "the default render is not 2 s of sppm"
expect 0 "" --backend cpu --width 32 --height 24 --photons 5000 -o "$tmp/t.png" --stats "$tmp/t.json" --time 0.3 --estimator radius
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['estimator']=='radius' and j['frames']>1 and j['wall_seconds']<5, j" "$tmp/t.json" \
  || fail "--time with an estimator"
expect 0 "" --backend cpu --width 32 --height 24 --photons 5000 -o "$tmp/t.png" --stats "$tmp/t.json" --time 100 --frames 3
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['frames']==3 and j['estimator']=='sppm', j" "$tmp/t.json" \
  || fail "--frames caps --time"
expect 0 "" "$scenes/bunny.json" --backend cpu --width 32 --height 24 --photons 5000 --frames 1 -o "$tmp/bunny.png"
expect 0 "" "$scenes/textured.glb" --backend cpu --width 32 --height 24 --photons 5000 --frames 1 -o "$tmp/textured.png"
expect 0 "" "$scenes/prism.json" "${small[@]}" -o "$tmp/prism.png"
expect 0 "" "${small[@]}" --spectral -o "$tmp/spectral.pfm"
expect 0 "" "${small[@]}" --wavelength 550 -o "$tmp/green.pfm"

# Bad input: exit 2 with the file, the place and the reason.
printf '{ "camera": { "position": [0, 0, 1], }' > "$tmp/broken.json"
expect 2 "broken.json: line 1" "$tmp/broken.json" "${small[@]}" -o "$tmp/x.png"
sed 's/"radius": 0.38, "material": "mirror"/"radius": -1, "material": "mirror"/' "$scenes/cornell.json" > "$tmp/negative.json"
expect 2 "negative.json: /objects/5/radius" "$tmp/negative.json" "${small[@]}" -o "$tmp/x.png"
sed 's/"type": "mirror", "reflectance"/"type": "metal", "reflectance"/' "$scenes/cornell.json" > "$tmp/metal.json"
expect 2 "metal.json: /materials/mirror/type" "$tmp/metal.json" "${small[@]}" -o "$tmp/x.png"
expect 2 "missing.json: cannot open scene file: No such file or directory" "$tmp/missing.json" "${small[@]}"
expect 2 "" "${small[@]}" --width 0
expect 2 "" "${small[@]}" --photons -5
expect 2 "--estimator: unknown value 'nearest'" "${small[@]}" --estimator nearest
expect 2 "--wavelength: must be in [360, 830] (got 300)" "${small[@]}" --wavelength 300
expect 2 "--wavelength: must be in [360, 830] (got 'nan', not a number)" "${small[@]}" --wavelength nan
sed 's/"type": "glass", "ior": 1.6, "abbe": 12/"type": "glass", "ior": 1.6, "abbe": -12/' "$scenes/prism.json" > "$tmp/abbe.json"
expect 2 "abbe.json: /materials/glass/abbe: must be in [1, 1e+06] (got -12)" "$tmp/abbe.json" "${small[@]}" -o "$tmp/x.png"
expect 2 "unknown image format" "${small[@]}" -o "$tmp/x.bmp"
expect 2 "" "${small[@]}" --no-such-option
expect 2 "'opencl' is not a backend" --backend opencl
expect 2 "'' is not a backend" --backend cpu,
expect 2 "--device '0,1': 2 entries for 3 devices" --backend cpu,cpu,cpu --device 0,1 -o "$tmp/x.png"
# Several devices split the frame's photon paths: the image of one, bit for bit.
"$render" "${small[@]}" --deterministic -o "$tmp/one.pfm" > /dev/null
"$render" "${small[@]:2}" --backend cpu,cpu --deterministic -o "$tmp/two.pfm" > /dev/null
cmp "$tmp/one.pfm" "$tmp/two.pfm" || fail "--backend cpu,cpu renders another image than cpu"

# Bad model files: exit 2 with the file, the OBJ line or the glTF pointer, and the reason.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n' > "$tmp/bad.obj"
expect 2 "bad.obj: line 4: vertex index '4' out of range" "$tmp/bad.obj" "${small[@]}" -o "$tmp/x.png"
printf '{"asset": {"version": "2.0"}, "extensionsRequired": ["EXT_texture_webp"], "extensionsUsed": ["EXT_texture_webp"]}' > "$tmp/webp.gltf"
expect 2 "webp.gltf: /extensionsRequired/0: the required extension 'EXT_texture_webp' is not supported" "$tmp/webp.gltf" "${small[@]}" -o "$tmp/x.png"

# Nothing to render is bad input, not a black image with exit 0.
triangle='"buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}], "bufferViews": [{"buffer": 0, "byteLength": 36}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}]'
printf '{"asset": {"version": "2.0"}, %s, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 1}]}], "nodes": [{"mesh": 0}]}' "$triangle" > "$tmp/lines.gltf"
expect 2 "lines.gltf: no triangles: its primitives are points or lines only" "$tmp/lines.gltf" "${small[@]}" -o "$tmp/x.png"
printf '{"asset": {"version": "2.0"}, %s, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": []}], "scene": 0}' "$triangle" > "$tmp/empty.gltf"
expect 2 "empty.gltf: no triangles: its scene has no nodes" "$tmp/empty.gltf" "${small[@]}" -o "$tmp/x.png"
printf '{"asset": {"version": "2.0"}, %s, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}]}' "$triangle" > "$tmp/one.gltf"
expect 0 "" "$tmp/one.gltf" "${small[@]}" -o "$tmp/x.png"
printf '{"asset": {"version": "1.0"}, "meshes": {"box": {"primitives": []}}}' > "$tmp/old.gltf"
expect 2 "old.gltf: a glTF 1.0 file; Photon reads glTF 2.0" "$tmp/old.gltf" "${small[@]}" -o "$tmp/x.png"
printf '{"camera": {"position": [0, 1, 4], "look_at": [0, 1, 0]}, "materials": {}, "lights": [{"type": "point", "position": [0, 3, 0], "power": 10}], "objects": []}' > "$tmp/nothing.json"
expect 2 "nothing.json: /objects: the scene has no geometry" "$tmp/nothing.json" "${small[@]}" -o "$tmp/x.png"
grep -q -- "--radius" "$tmp/err" && fail "a scene without geometry blames --radius"
printf '\xef\xbb\xbfv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$tmp/bom.obj"
expect 0 "" "$tmp/bom.obj" "${small[@]}" -o "$tmp/x.png"

# A mesh's warnings name the mesh file and where the scene file names it (a scene's "name" is
# often empty); a model rendered by itself names the model.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n' > "$tmp/flat.obj"
mesh_scene flat.obj "0.3, 0.3, 3" "0.3, 0.3, 0" "0, 1, 2" > "$tmp/warn.json"
expect 0 "flat.obj ($tmp/warn.json: /objects/0/file): 1 triangle without area (or not finite) dropped" "$tmp/warn.json" "${small[@]}" -o "$tmp/x.png"
expect 0 "flat.obj: 1 triangle without area (or not finite) dropped" "$tmp/flat.obj" "${small[@]}" -o "$tmp/x.png"

# Files a model names stay in its folder tree, unless --allow-outside-paths.
mkdir -p "$tmp/model"
printf 'newmtl red\nKd 1 0 0\n# SECRET\n' > "$tmp/outside.mtl"
printf 'mtllib ../outside.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$tmp/model/m.obj"
expect 2 "m.obj: mtllib '" "$tmp/model/m.obj" "${small[@]}" -o "$tmp/x.png"
grep -q "lies outside the model's folder (--allow-outside-paths reads it)" "$tmp/err" && ! grep -q SECRET "$tmp/err" ||
  { fail "the refusal of outside.mtl"; cat "$tmp/err"; }
expect 0 "" "$tmp/model/m.obj" "${small[@]}" -o "$tmp/x.png" --allow-outside-paths
mesh_scene model/m.obj "0.3, 0.3, 3" "0.3, 0.3, 0" "0, 1, 2" > "$tmp/outer.json"
expect 2 "outer.json: /objects/0/file: " "$tmp/outer.json" "${small[@]}" -o "$tmp/x.png"
expect 0 "" "$tmp/outer.json" "${small[@]}" -o "$tmp/x.png" --allow-outside-paths
mesh_scene gone.obj "0, 1, 4" "0, 1, 0" "0, 3, 0" > "$tmp/gone.json"
expect 2 "gone.json: /objects/0/file: " "$tmp/gone.json" "${small[@]}" -o "$tmp/x.png"

# Issue 38: every documented form works as written, and no message grows with its input.
expect 0 "" "${small[@]}" -o "$tmp/x.png" --no-quiet --no-validation --no-allow-outside-paths
expect 0 "" "${small[@]}" -o "$tmp/x.png" --quiet --no-quiet
[ -s "$tmp/err" ] || fail "--quiet --no-quiet printed nothing"
expect 2 "--output: an empty file name" "${small[@]}" -o ''
expect 2 "--stats: an empty file name" "${small[@]}" -o "$tmp/x.png" --stats ''
# A scene file with a key of 3 MB: its JSON pointer is in the message.
long=$(head -c 3000000 /dev/zero | tr '\0' 'x')
printf '{"%s": 1}' "$long" >"$tmp/longkey.json"
"$render" "$tmp/longkey.json" "${small[@]}" -o "$tmp/x.png" >"$tmp/out" 2>"$tmp/err"
code=$?
bytes=$(wc -c <"$tmp/err")
if [ "$code" -ne 2 ] || [ "$bytes" -gt 1001 ] || [ "$(wc -l <"$tmp/err")" -ne 1 ] || ! grep -qF "bytes cut]" "$tmp/err" ||
   ! grep -qF "unknown key" "$tmp/err"; then
  fail "a 3 MB key gave exit $code and $bytes bytes of message: $(head -c 300 "$tmp/err")"
else
  echo "ok: exit 2: a 3 MB key, a message of $bytes bytes"
fi
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1e30\nv 1 0 1e30\nv 0 1 1e30\nf 1 2 3\nf 4 5 6\n' > "$tmp/far.obj"
expect 2 "far.obj: the model's triangles are 1e+30 wide (z from 0 to 1e+30)" "$tmp/far.obj" "${small[@]}" -o "$tmp/x.png"
grep -q -- "--radius" "$tmp/err" && fail "a model at 1e30 blames --radius"
mesh_scene far.obj "0, 1, 4" "0, 1, 0" "0, 3, 0" > "$tmp/far.json"
expect 2 "far.json: /objects/0/file: $tmp/far.obj: the model's triangles are 1e+30 wide" "$tmp/far.json" "${small[@]}" -o "$tmp/x.png"
# A black image with exit 0 says so (a camera looking away from the only lit object).
printf '{"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1]}, "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}, "lights": [{"type": "point", "position": [0, 0, -3], "power": 10}], "objects": [{"type": "sphere", "center": [0, 0, -4], "radius": 0.5, "material": "grey"}]}' > "$tmp/away.json"
expect 0 "away.json: the image is nearly black: 0.0% of its pixels show" "$tmp/away.json" "${small[@]}" -o "$tmp/x.png" --stats "$tmp/away-stats.json"
grep -q "nearly black" "$tmp/away-stats.json" || fail "the stats lack the warning"
# --aov into a file that cannot hold the auxiliary images says so (issue 57); an EXR file does not.
expect 0 "x.png: only an .exr file holds the auxiliary images" "${small[@]}" --aov -o "$tmp/x.png"
expect 0 "" "${small[@]}" --aov -o "$tmp/x.exr"
grep -q "auxiliary" "$tmp/err" && fail "an EXR output warned of auxiliary images"

bench="$(dirname "$render")/photon-bench"
"$bench" --resolutions 99999x99999 >"$tmp/out" 2>"$tmp/err"
if [ $? -ne 2 ] || ! grep -qF -- "--resolutions: '99999x99999': the width 99999 is not in [1, 16384] (--width's range)" "$tmp/err"; then
  fail "photon-bench --resolutions 99999x99999"; cat "$tmp/err"
else
  echo "ok: exit 2: photon-bench --resolutions 99999x99999"
fi

# Runtime failure: a backend this machine cannot run.
if ! command -v nvidia-smi >/dev/null 2>&1; then
  expect 1 "CUDA" --backend cuda --width 8 --height 8 -o "$tmp/x.png"
fi

# photon-converge --camera-path: the error of a moving view; a path it does not know is refused.
converge="$(dirname "$render")/photon-converge"
"$converge" "$scenes/cornell.json" --backend cpu --camera-path orbit:2 --path-frames 4 --samples 2 \
  --reference-frames 2 --set width=32 --set height=24 --set photons=2000 --json "$tmp/orbit.json" >"$tmp/out" 2>"$tmp/err"
if [ $? -ne 0 ] || ! grep -q '"reproject_denoised"' "$tmp/orbit.json"; then
  fail "photon-converge --camera-path"; cat "$tmp/err"
else
  echo "ok: photon-converge --camera-path orbit:2"
fi
"$converge" "$scenes/cornell.json" --camera-path spin:3 >"$tmp/out" 2>"$tmp/err"
if [ $? -ne 2 ] || ! grep -qF -- "--camera-path: 'spin:3' is not orbit:SECONDS" "$tmp/err"; then
  fail "photon-converge --camera-path spin:3"; cat "$tmp/err"
else
  echo "ok: exit 2: photon-converge --camera-path spin:3"
fi

[ "$failures" -eq 0 ] && echo "all CLI checks passed"
exit "$failures"
