#!/usr/bin/env bash
# Renders every shipped scene with --deterministic on the given backends and prints one SHA-256 per
# image, so that a change meant to alter nothing (a refactoring) can show that the images are the
# same bit for bit: run it before and after, and diff the two lists.
#   tools/image_hashes.sh build/release/bin/photon-render OUT_DIR [cpu,vulkan]
# Each scene renders at 96×72 with 20 000 photons, 3 frames, under the default estimator (sppm) and
# under k nearest with final gather, so that both halves of the gather stage are covered.
set -euo pipefail
render=$1
out=$2
backends=${3:-cpu,vulkan}
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$out"
variants=("default:" "knn-fg:--estimator knn --global final-gather")
for scene in "$root"/scenes/*.json "$root"/scenes/*.glb; do
  name=$(basename "$scene")
  for backend in ${backends//,/ }; do
    for variant in "${variants[@]}"; do
      tag=${variant%%:*}
      # shellcheck disable=SC2086
      "$render" "$scene" --backend "$backend" --deterministic --width 96 --height 72 --photons 20000 \
        --frames 3 --seed 7 ${variant#*:} -o "$out/$name.$backend.$tag.exr" > /dev/null
    done
  done
done
(cd "$out" && sha256sum -- *.exr)
