#!/usr/bin/env bash
# Builds the scene-loader fuzz target with clang in its own build directory and runs it for $1
# seconds (default 60), seeded with scenes/*.json. Exits non-zero if libFuzzer finds a crash, a
# sanitizer report, a leak or a slow input; the input that did it is left in <build>/fuzz-artifacts.
# Usage: tests/fuzz/run.sh [seconds] [build-dir]   (build-dir defaults to build-fuzz)
set -euo pipefail

seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$(realpath -m "${2:-$root/build-fuzz}")"

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPHOTON_FUZZ=ON -DPHOTON_CUDA=OFF -DPHOTON_VULKAN=OFF -DPHOTON_VIEWER=OFF -DPHOTON_TESTS=OFF
cmake --build "$build" --target scene_loader_fuzz --parallel "$(nproc)"

corpus="$build/fuzz-corpus"
artifacts="$build/fuzz-artifacts"
rm -rf "$corpus" "$artifacts"
mkdir -p "$corpus" "$artifacts"
cp "$root"/scenes/*.json "$corpus"/

status=0
"$build/bin/scene_loader_fuzz" "$corpus" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
  -timeout=10 -artifact_prefix="$artifacts/" -print_final_stats=1 || status=$?
if [ "$status" -ne 0 ]; then
  echo "scene_loader_fuzz failed (exit $status); reproducer(s) in $artifacts:" >&2
  ls -l "$artifacts" >&2
fi
exit "$status"
