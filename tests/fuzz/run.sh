#!/usr/bin/env bash
# Builds the fuzz targets with clang (AddressSanitizer, UBSan, fuzzer coverage over the core and the
# CPU backend) in their own build directory and runs each for $1 seconds (default 60), seeded from
# the shipped scenes (scenes/*.json, *.obj), the committed corpus in tests/fuzz/corpus/ (its
# environment maps are written by photon-make-environment-corpus, its .vdb file by
# photon-make-smoke-vdb) and the inputs earlier runs found
# crashes with, in tests/fuzz/findings/ (bad files the loaders must refuse with a message). Exits non-zero if libFuzzer
# finds a crash, a sanitizer report, a leak or a slow input; the input that did it is left in
# <build>/fuzz-artifacts/<target>.
# Usage: tests/fuzz/run.sh [seconds] [build-dir]   (build-dir defaults to build-fuzz)
set -euo pipefail

seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$(realpath -m "${2:-$root/build-fuzz}")"
sanitize="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=all -fno-omit-frame-pointer"

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" \
  -DPHOTON_FUZZ=ON -DPHOTON_CUDA=OFF -DPHOTON_VULKAN=OFF -DPHOTON_VIEWER=OFF -DPHOTON_TESTS=OFF
targets=(scene_loader_fuzz render_fuzz obj_loader_fuzz gltf_loader_fuzz environment_loader_fuzz vdb_loader_fuzz)
cmake --build "$build" --target "${targets[@]}" --parallel "$(nproc)"

status=0
for target in "${targets[@]}"; do
  corpus="$build/fuzz-corpus/$target"
  artifacts="$build/fuzz-artifacts/$target"
  rm -rf "$corpus" "$artifacts"
  mkdir -p "$corpus" "$artifacts"
  case "$target" in
    scene_loader_fuzz | render_fuzz) cp "$root"/scenes/*.json "$corpus"/ ;;
    obj_loader_fuzz) cp "$root"/scenes/*.obj "$corpus"/ ;;
  esac
  for committed in corpus findings; do
    if [ -d "$root/tests/fuzz/$committed/$target" ]; then
      cp "$root/tests/fuzz/$committed/$target"/* "$corpus"/
    fi
  done
  echo "== $target for $seconds s"
  "$build/bin/$target" "$corpus" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
    -timeout=10 -artifact_prefix="$artifacts/" -print_final_stats=1 || {
    code=$?
    echo "$target failed (exit $code); reproducer(s) in $artifacts:" >&2
    ls -l "$artifacts" >&2
    status=$code
  }
done
exit "$status"
