#!/usr/bin/env bash
# glTF as the web ships it renders as the original does: gltfpack's quantized (KHR_mesh_quantization,
# with the node transforms that dequantize), meshopt-compressed (EXT_meshopt_compression) and
# Draco-compressed (KHR_draco_mesh_compression, assimp's test model) files, made here at test time,
# give the original's mean radiance within 1%.
#   tests/gltfpack_test.sh <photon-render> <scenes dir> <work dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
render=$1
scenes=$2
work=$3
models=/usr/share/assimp/models/glTF2
rm -rf "$work"
mkdir -p "$work"

if ! command -v gltfpack >/dev/null 2>&1; then
  echo "FAIL: gltfpack is not installed (tools/install-deps.sh installs it)"
  exit 1
fi

# pack <out> <gltfpack options...>: gltfpack's output, or a failure.
pack() {
  local out=$1
  shift
  gltfpack "$@" -o "$out" >"$work/gltfpack.log" 2>&1 || { fail "gltfpack $* failed"; cat "$work/gltfpack.log"; }
}

# mean <input> <image.pfm>: renders it (the sizes and frames of the task) and prints the mean radiance.
mean() {
  "$render" "$1" --backend cpu --width 64 --height 48 --frames 4 -q -o "$2" || { fail "photon-render $1 failed"; echo nan; return; }
  python3 - "$2" <<'EOF'
import array, sys
data = open(sys.argv[1], 'rb').read()
header, size, scale, pixels = data.split(b'\n', 3)
values = array.array('f')
values.frombytes(pixels)
print(sum(values) / len(values))
EOF
}

# same <what> <reference mean> <mean>: within 1%.
same() {
  if python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); sys.exit(0 if a > 0 and abs(b - a) <= 0.01 * a else 1)" "$2" "$3"; then
    echo "ok: $1: $3 against $2"
  else
    fail "$1: mean radiance $3, the original's $2 (more than 1% apart)"
  fi
}

# 1. textured.glb as a whole scene (its camera, lights and textures), meshopt-compressed floats.
#    (gltfpack's quantization also rescales texture coordinates through KHR_texture_transform,
#    which the material code reads, not the loader: part 2 renders quantized geometry.)
pack "$work/textured-c-noq.glb" -c -noq -i "$scenes/textured.glb"
reference=$(mean "$scenes/textured.glb" "$work/textured.pfm")
same "textured.glb, gltfpack -c -noq" "$reference" "$(mean "$work/textured-c-noq.glb" "$work/textured-c-noq.pfm")"

# 2. Its geometry under one scene material: quantized, and quantized and meshopt-compressed.
under_material() {
  local model=$1 scene=$2
  cat >"$scene" <<EOF
{"camera": {"position": [0.6, 1.6, 4.6], "look_at": [0, 0.8, 0], "fov": 45},
 "materials": {"grey": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]}},
 "objects": [{"type": "mesh", "file": "$model", "material": "grey"}],
 "lights": [{"type": "point", "position": [1, 3, 2], "power": 60}]}
EOF
}
cp "$scenes/textured.glb" "$work/textured.glb"
under_material textured.glb "$work/grey.json"
reference=$(mean "$work/grey.json" "$work/grey.pfm")
for options in "" "-c" "-cc"; do
  name="textured${options:+$options}.glb"
  # shellcheck disable=SC2086
  pack "$work/$name" $options -i "$scenes/textured.glb"
  under_material "$name" "$work/grey$options.json"
  same "textured.glb geometry, gltfpack $options" "$reference" "$(mean "$work/grey$options.json" "$work/grey$options.pfm")"
done

# 3. assimp's test models: a binary glTF packed three ways, and the same engine Draco-compressed.
if [ -d "$models" ]; then
  engine="$models/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
  reference=$(mean "$engine" "$work/engine.pfm")
  for options in "" "-c" "-cc"; do
    # shellcheck disable=SC2086
    pack "$work/engine$options.glb" $options -i "$engine"
    same "2CylinderEngine.glb, gltfpack $options" "$reference" "$(mean "$work/engine$options.glb" "$work/engine$options.pfm")"
  done
  same "2CylinderEngine, KHR_draco_mesh_compression" "$reference" "$(mean "$models/draco/2CylinderEngine.gltf" "$work/engine-draco.pfm")"
else
  fail "no $models (tools/install-deps.sh installs assimp-testmodels)"
fi

[ "$failures" -eq 0 ] && echo "all gltfpack checks passed"
exit "$failures"
