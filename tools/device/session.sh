#!/usr/bin/env bash
# Runs on the GPU machine (see ../shared/device/README.md) from the project root, with the
# binaries of `cmake --preset device && cmake --build --preset device` carried in build-device/bin
# and .devlibs/ prepared. Writes logs and JSON under $OUT.
#   tools/device/session.sh tests sanitize bench grid launch vulkan
set -uo pipefail
source .devlibs/setup.sh >/dev/null
bin=build-device/bin
out=${OUT:-/tmp/photon-out}
mkdir -p "$out"
export PHOTON_SCENES_DIR=$PWD/scenes PHOTON_TEST_DATA_DIR=$PWD/tests/data PHOTON_TEST_OUTPUT_DIR=$out
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,memory.total --format=csv,noheader
summary=()
for step in "$@"; do
  case $step in
    tests)
      $bin/photon_tests --gtest_filter='CudaVsCpu*:Vulkan*' >"$out/tests.log" 2>&1
      summary+=("tests: $(grep -E '^\[  (PASSED|FAILED) ' "$out/tests.log" | tr '\n' ' ')")
      grep -E "FAILED|Failure|Expected|actual|Which is" "$out/tests.log" | head -20 ;;
    sanitize)
      for tool in memcheck racecheck; do
        compute-sanitizer --tool $tool --error-exitcode 9 $bin/photon-render --backend cuda --width 160 --height 120 \
          --photons 50000 --frames 2 -o "$out/sanitize.png" >"$out/$tool.log" 2>&1
        summary+=("$tool: exit $? $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$out/$tool.log" | tr '\n' ' ')")
      done ;;
    bench)
      $bin/photon-bench --backends ${BACKENDS:-cuda} --resolutions 1920x1080,3840x2160 --photons 1000000 --frames 50 ${VARY:-} \
        --json "$out/bench.json" --csv "$out/bench.csv" | tee "$out/bench.log" ;;
    series)
      $bin/photon-bench --backends cuda,cpu --cpu-frames 1 --resolutions 640x480,800x600,1024x768,1280x720,1920x1080,2560x1600,3840x2400 \
        --photons 1000000 --frames 30 --json "$out/series.json" | tee "$out/series.log" ;;
    grid)
      $bin/photon-bench --backends cuda --grid-sweep 1000000,2000000,4000000,8000000,16000000 --frames 30 \
        --json "$out/grid.json" | tee "$out/grid.log" ;;
    launch)
      $bin/photon-bench --backends cuda --resolutions 1920x1080 --photons 1000000 --launch-sweep --frames 30 ${VARY:-} \
        --json "$out/launch.json" | tee "$out/launch.log" ;;
    startup)
      for i in 1 2 3; do
        s=$(date +%s%N); $bin/photon-render --backend cuda --width 1920 --height 1080 --photons 1000000 -o "$out/first.png" -q; e=$(date +%s%N)
        summary+=("process start to image file, run $i: $(( (e - s) / 1000000 )) ms")
      done ;;
    profile)
      # Nsight Compute on one gather launch at 1080p (after a warm-up frame), plus each view's times.
      ncu --kernel-name regex:gather --launch-skip 1 --launch-count 1 --section SpeedOfLight --section Occupancy \
        --section WarpStateStats --section SchedulerStats --section MemoryWorkloadAnalysis --section LaunchStats \
        --section SourceCounters $bin/photon-render --backend cuda --width 1920 --height 1080 --photons 1000000 \
        --frames 2 -o "$out/profile.png" -q >"$out/ncu.log" 2>&1
      grep -E "Duration|Achieved Occupancy|Theoretical Occupancy|Registers|Warp Cycles Per Issued|Issue Slots Busy|No Eligible|L1/TEX Hit|L2 Hit|Memory Throughput|Compute \(SM\)|Stall|Branch Efficiency|Avg. Active Threads|Avg. Not Predicated" "$out/ncu.log" | head -40
      for view in final global caustic direct; do
        $bin/photon-render --backend cuda --width 1920 --height 1080 --photons 1000000 --frames 30 --view $view ${RENDER_ARGS:-} \
          -o "$out/view.png" --stats "$out/view-$view.json" -q
        summary+=("view $view: gather median $(python3 -c "import json;print(json.load(open('$out/view-$view.json'))['stages']['gather']['median_ms'])") ms")
      done ;;
    progressive)
      $bin/photon-bench --backends cuda,vulkan --resolutions 1920x1080,3840x2160 --photons 1000000 \
        --estimator progressive --frames 64 --warmup 1 --json "$out/progressive.json" | tee "$out/progressive.log" ;;
    viewer)
      # The viewer's frame loop rendering offscreen (no display here), validated first.
      $bin/photon-view scenes/cornell.json --offscreen --frames 30 --validation --screenshot "$out/view-nvidia.png" \
        >"$out/viewer.log" 2>&1; summary+=("viewer validated run: exit $? $(tail -1 "$out/viewer.log")")
      for r in 640x480 1920x1080; do
        w=${r%x*}; h=${r#*x}
        for v in final dots; do
          $bin/photon-view scenes/cornell.json --offscreen --frames 300 --width $w --height $h --photons 1000000 \
            --view $v --stats "$out/view-$v-$r.json" >>"$out/viewer.log" 2>&1
          summary+=("viewer $v $r: $(tail -1 "$out/viewer.log")")
        done
      done ;;
    render)
      for scene in cornell mirrors; do
        $bin/photon-render scenes/$scene.json --backend cuda --width 1280 --height 960 --photons 2000000 --frames 256 \
          -o "$out/$scene.png" --stats "$out/$scene-stats.json" -q
      done ;;
      bundle)
      # Only 8 files come back: everything but the pictures goes into one archive.
      (cd "$out" && tar czf /tmp/results.tgz --exclude '*.png' --exclude '*.exr' . &&
        find . -type f ! -name '*.png' -delete && mv /tmp/results.tgz .) ;;
  esac
done
printf '%s\n' "${summary[@]}"
