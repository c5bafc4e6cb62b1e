#!/usr/bin/env bash
# Runs on the GPU machine (its notes are outside this repository, in shared/device/README.md beside
# the checkouts) from the project root, with the
# binaries of `cmake --preset device && cmake --build --preset device` carried in build-device/bin
# and .devlibs/ prepared by tools/device/prepare.sh. Writes logs and JSON under $OUT.
#   tools/device/session.sh tests sanitize sanitize-new environment frames meshes wide converge spectral compact pictures bundle-all
set -uo pipefail
source .devlibs/setup.sh >/dev/null
bin=build-device/bin
out=${OUT:-/tmp/photon-out}
mkdir -p "$out"
export PHOTON_SCENES_DIR=$PWD/scenes PHOTON_TEST_DATA_DIR=$PWD/tests/data PHOTON_TEST_OUTPUT_DIR=$out
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,memory.total --format=csv,noheader
summary=()
# sanitize TAG RUN...: each RUN (photon-render arguments) under memcheck and racecheck at 96x72 with
# 30000 photons, logged to $out/<tool>-TAG.log, one summary line each.
sanitize() {
  local tag=$1 tool run
  shift
  for tool in memcheck racecheck; do
    for run in "$@"; do
      compute-sanitizer --tool $tool --error-exitcode 9 $bin/photon-render $run --backend cuda --width 96 --height 72 \
        --photons 30000 -o "$out/sanitize.png" -q >>"$out/$tool-$tag.log" 2>&1
      summary+=("$tool $run: exit $?")
    done
  done
}
for step in "$@"; do
  case $step in
    tests)
      $bin/photon_tests --gtest_filter='CudaVsCpu*:Vulkan*:Environment*' >"$out/tests.log" 2>&1
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
    ncu)
      # Issue 19: what limits each stage. Nsight Compute on one launch of each kernel of a 1080p
      # frame (after warm-up), scene SCENE (cornell built in), estimator ESTIMATOR (sppm).
      for k in tracePhotonsKernel tracePixelsKernel gatherKernel accumulateKernel countCellsKernel scatterPhotonsKernel; do
        ncu --kernel-name regex:"$k" --launch-skip 2 --launch-count 1 --section SpeedOfLight --section Occupancy \
          --section LaunchStats --section WarpStateStats --section MemoryWorkloadAnalysis --section SchedulerStats \
          --section ComputeWorkloadAnalysis $bin/photon-render ${SCENE:-} --backend cuda --width 1920 --height 1080 \
          --photons 1000000 --frames 4 --estimator ${ESTIMATOR:-sppm} -o "$out/ncu.png" -q >"$out/ncu-$k.log" 2>&1
        echo "== $k"
        grep -E "^ +(Duration|Registers Per Thread|Achieved Occupancy|Theoretical Occupancy|Block Limit Registers|Compute \(SM\) Throughput|Memory Throughput|L1/TEX Hit Rate|L2 Hit Rate|DRAM Throughput|Issue Slots Busy|No Eligible|Warp Cycles Per Issued Instruction|Avg. Active Threads Per Warp|Local Memory Spilling Requests|Dynamic Shared|Stack Size|Executed Ipc Active) " "$out/ncu-$k.log" | sed -E 's/ +/ /g'
        grep -E "Stall|stall" "$out/ncu-$k.log" | head -4 | cut -c1-300
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
    environment)
      # Issue 18: the sky scene against the same scene under a point light where its sun is, the
      # share of environment photons that hit the scene, a 4096x2048 map's distribution build,
      # the new kernels under compute-sanitizer, and the README picture.
      sc=$out/env-scenes; mkdir -p "$sc"; cp scenes/sky.json "$sc/sky.json"
      sed 's|{ "type": "sky"[^}]*}|{ "type": "point", "position": [-2.4, 3.0, -3.8], "power": 900 }|' scenes/sky.json >"$sc/sky_point.json"
      sed 's|"turbidity": 3 }|"turbidity": 3, "resolution": [4096, 2048] }|' scenes/sky.json >"$sc/sky_4k.json"
      $bin/photon-bench --scenes-dir "$sc" --scenes sky,sky_point --backends cuda,vulkan --resolutions 1920x1080 \
        --photons 1000000 --frames 50 --json "$out/environment.json" | tee "$out/environment.log"
      $bin/photon-render "$sc/sky_4k.json" --backend cuda --width 1920 --height 1080 --photons 1000000 --frames 20 \
        -o "$out/sky_4k.png" --stats "$out/sky_4k.json" -q
      summary+=("sky 4096x2048: $(python3 -c "import json;d=json.load(open('$out/sky_4k.json'));print('distribution build', d['scene_stats']['environment']['distribution_build_seconds'], 's; environment photons hitting the scene', d['environment']['hit_fraction'])")")
      sanitize environment "scenes/sky.json --frames 3" "scenes/bunny.obj --frames 3 --deterministic"
      $bin/photon-render scenes/sky.json --backend cuda --width 960 --height 720 --photons 2000000 --time 2 \
        -o "$out/sky.png" --stats "$out/sky-stats.json" -q ;;
    render)
      for scene in cornell mirrors; do
        $bin/photon-render scenes/$scene.json --backend cuda --width 1280 --height 960 --photons 2000000 --frames 256 \
          -o "$out/$scene.png" --stats "$out/$scene-stats.json" -q
      done ;;
    sanitize-new)
      # The kernels of the mesh, sppm and primary-ray work: the BVH traversal, textures, emissive
      # triangles, directional light, the sppm estimates and their running mean.
      sanitize new "scenes/bunny.json --estimator sppm --frames 3" "scenes/textured.glb --estimator sppm --frames 3" \
        "scenes/smallpt.json --estimator sppm --frames 3 --deterministic"
      compute-sanitizer --tool memcheck --error-exitcode 9 $bin/photon-bench --backends cuda --scenes mesh:20000 \
        --resolutions 96x72 --photons 20000 --frames 2 --warmup 1 --primary-rays >>"$out/memcheck-new.log" 2>&1
      summary+=("memcheck primary rays: exit $?")
      grep -E "ERROR SUMMARY|RACECHECK SUMMARY" "$out"/memcheck-new.log "$out"/racecheck-new.log | sort | uniq -c | head ;;
    meshes)
      # Issue 10: BVH build, primary rays and photon paths over triangle counts, the mesh scenes.
      $bin/photon-bench --scenes-dir scenes --backends cuda,vulkan --scenes mesh:10000,mesh:100000,mesh:1000000,mesh:10000000 \
        --resolutions 1920x1080 --photons 1000000 --frames 30 --primary-rays --json "$out/meshes.json" | tee "$out/meshes.log"
      $bin/photon-bench --scenes-dir scenes --backends cuda,vulkan --scenes bunny,scenes/textured.glb,mesh-glass:1000000 \
        --resolutions 1920x1080 --photons 1000000 --frames 50 --primary-rays --json "$out/mesh-scenes.json" | tee "$out/mesh-scenes.log" ;;
    wide)
      # Issue 19 item 4: the four-wide BVH (photon-bench) against the binary one it replaced
      # (photon-bench-binary, carried beside it), side by side: the mesh sweep and the mesh scenes,
      # primary rays and photon paths, on both GPU backends.
      for b in photon-bench-binary photon-bench; do
        echo "== $b" | tee -a "$out/wide.log"
        $bin/$b --scenes-dir scenes --backends cuda,vulkan --scenes mesh:10000,mesh:100000,mesh:1000000,mesh:10000000 \
          --resolutions 1920x1080 --photons 1000000 --frames 30 --primary-rays --json "$out/wide-$b.json" 2>&1 \
          | grep -v "first image" | tee -a "$out/wide.log"
        $bin/$b --scenes-dir scenes --backends cuda,vulkan --scenes bunny,scenes/textured.glb,mesh-glass:1000000 \
          --resolutions 1920x1080 --photons 1000000 --frames 50 --primary-rays --json "$out/wide-scenes-$b.json" 2>&1 \
          | grep -v "first image" | tee -a "$out/wide.log"
      done ;;
    frames)
      # The analytic Cornell box's frame (no regression), each estimator, and the cost of --deterministic.
      $bin/photon-bench --backends cuda,vulkan --resolutions 1920x1080,3840x2160 --photons 1000000 --frames 50 \
        --vary estimator=radius,sppm --json "$out/frames.json" | tee "$out/frames.log"
      $bin/photon-bench --backends cuda,vulkan --resolutions 1920x1080 --photons 1000000 --frames 50 \
        --vary deterministic=false,true --json "$out/deterministic.json" | tee "$out/deterministic.log" ;;
    frames-ab)
      # The Cornell frame before this work (photon-bench-old: commit 074b423), now without the
      # read-only loads (photon-bench-plain: -DPHOTON_NO_READ_ONLY_LOADS) and now, each carried
      # beside the build, at the old defaults: the progressive estimator, radii 0.04 and 0.02.
      for b in photon-bench-old photon-bench-plain photon-bench; do
        echo "== $b" | tee -a "$out/ab.log"
        $bin/$b --backends cuda,vulkan --resolutions 1920x1080,3840x2160 --photons 1000000 --frames 64 \
          --estimator progressive --vary radius=0.04 --vary caustic_radius=0.02 2>&1 | grep -v "first image" | tee -a "$out/ab.log"
      done
      for b in photon-bench-plain photon-bench; do
        echo "== $b meshes" | tee -a "$out/ab.log"
        $bin/$b --scenes-dir scenes --backends cuda --scenes bunny,mesh:1000000 --resolutions 1920x1080 --photons 1000000 \
          --frames 50 --primary-rays 2>&1 | grep -v "first image" | tee -a "$out/ab.log"
      done ;;
    converge)
      # Issue 11: converged references (sppm, 4096 frames of 4M photons), then error against GPU time.
      for scene in smallpt caustic cornell; do
        $bin/photon-render scenes/$scene.json --backend cuda --estimator sppm --width 256 --height 192 --pixel-center \
          --frames ${REF_FRAMES:-4096} --photons 4000000 --seed 99 -o "$out/ref-$scene.pfm" -q
        summary+=("reference $scene: exit $?")
        $bin/photon-converge scenes/$scene.json --reference "$out/ref-$scene.pfm" --backend cuda \
          --estimators sppm,progressive,radius,knn,cell --set width=256 --set height=192 --set pixel_center=true \
          --set photons=1000000 --frames ${CONVERGE_FRAMES:-1024} --json "$out/converge-$scene.json" | tee "$out/converge-$scene.log"
      done ;;
    reference-cornell)
      # Issue 20: the default Cornell box (640x480, jittered pixels) converged, for the CPU's first seconds.
      $bin/photon-render scenes/cornell.json --backend cuda --estimator sppm --frames ${REF_FRAMES:-4096} \
        --photons 2000000 --seed 99 -o "$out/ref-cornell-640x480.pfm" -q
      summary+=("reference cornell 640x480: exit $?") ;;
    spectral)
      # Issue 21: the spectral frame against the RGB one, converged references of the Cornell box in
      # both modes and of the dispersive gem, error against GPU time in both modes, the spectral
      # kernels under compute-sanitizer, and the pictures.
      $bin/photon-bench --backends cuda,vulkan --resolutions 1920x1080,3840x2160 --photons 1000000 --frames 50 \
        --vary spectral=false,true --json "$out/spectral-bench.json" | tee "$out/spectral-bench.log"
      for mode in rgb spectral; do
        flag=""; [ $mode = spectral ] && flag="--spectral"
        $bin/photon-render scenes/cornell.json --backend cuda --estimator sppm --frames ${REF_FRAMES:-4096} \
          --photons 2000000 --seed 99 $flag -o "$out/ref-cornell-$mode.pfm" -q
        summary+=("reference cornell $mode: exit $?")
        $bin/photon-converge scenes/cornell.json --reference "$out/ref-cornell-$mode.pfm" --backend cuda \
          --estimators sppm --set spectral=$([ $mode = spectral ] && echo true || echo false) --set photons=500000 \
          --frames ${CONVERGE_FRAMES:-1024} --json "$out/converge-cornell-$mode.json" | tee "$out/converge-cornell-$mode.log"
      done
      $bin/photon-converge scenes/cornell.json --reference "$out/ref-cornell-rgb.pfm" --compare "$out/ref-cornell-spectral.pfm" \
        | tee "$out/spectral-vs-rgb.log"
      $bin/photon-render scenes/gem.json --backend cuda --estimator sppm --frames ${REF_FRAMES:-4096} --photons 2000000 \
        --seed 99 -o "$out/ref-gem.pfm" -q
      summary+=("reference gem: exit $?")
      $bin/photon-converge scenes/gem.json --reference "$out/ref-gem.pfm" --backend cuda --estimators sppm,progressive \
        --set photons=1000000 --window ${GEM_WINDOW:-296,290,336,316} --frames ${CONVERGE_FRAMES:-1024} --json "$out/converge-gem.json" | tee "$out/converge-gem.log"
      sanitize spectral "scenes/prism.json --frames 3" "scenes/gem.json --frames 3 --estimator radius" \
        "scenes/cornell.json --frames 2 --spectral --deterministic"
      for scene in prism gem; do
        $bin/photon-render scenes/$scene.json --backend cuda --width 1280 --height 800 --photons 2000000 --time 3 \
          -o "$out/picture-$scene.png" -q
        summary+=("picture $scene: exit $?")
      done ;;
    compact)
      # Issue 21 item 3: the maps' 16-byte photon against the 32-byte one of before (photon-bench-old,
      # commit 4246152, carried beside the build), side by side: the Cornell box in both modes and
      # each radius estimator, photon counts 1M..16M, the bunny; then converged Cornell images of
      # both builds, compared with each other and, for the noise between two seeds, old with old.
      for b in photon-bench-old photon-bench; do
        echo "== $b" | tee -a "$out/compact.log"
        $bin/$b --backends cuda,vulkan --resolutions 1920x1080,3840x2160 --photons 1000000 --frames 50 \
          --vary estimator=sppm,progressive,knn 2>&1 | grep -v "first image" | tee -a "$out/compact.log"
        $bin/$b --backends cuda --resolutions 1920x1080 --photons 1000000,4000000,16000000 --frames 30 \
          --vary spectral=false,true 2>&1 | grep -v "first image" | tee -a "$out/compact.log"
        $bin/$b --scenes-dir scenes --backends cuda,vulkan --scenes bunny,gem --resolutions 1920x1080 --photons 1000000 \
          --frames 50 2>&1 | grep -v "first image" | tee -a "$out/compact.log"
      done
      for b in photon-render-old:1 photon-render-old:2 photon-render:1; do
        $bin/${b%:*} scenes/cornell.json --backend cuda --width 320 --height 240 --frames 1024 --photons 2000000 \
          --seed ${b#*:} -o "$out/compact-${b%:*}-${b#*:}.pfm" -q
        summary+=("$b: exit $?")
      done
      for pair in "photon-render-old-2 photon-render-old-1" "photon-render-1 photon-render-old-1" "photon-render-1 photon-render-old-2"; do
        read -r a r <<<"$pair"
        summary+=("$a vs $r: $($bin/photon-converge --compare "$out/compact-$a.pfm" --reference "$out/compact-$r.pfm" 2>&1 | tail -1)")
      done ;;
    table)
      # The README's benchmark table: the default frame at both sizes, the progressive frame at the
      # radii the table names, the bunny and the 1M-triangle mesh, with the primary-ray rate.
      $bin/photon-bench --backends cuda,vulkan --resolutions 1920x1080,3840x2160 --photons 1000000 --frames 50 \
        --json "$out/table-cornell.json" 2>&1 | grep -v "first image" | tee "$out/table.log"
      $bin/photon-bench --backends cuda --resolutions 1920x1080 --photons 1000000 --frames 50 --estimator progressive \
        --vary radius=0.04 --vary caustic_radius=0.02 2>&1 | grep -v "first image" | tee -a "$out/table.log"
      $bin/photon-bench --scenes-dir scenes --backends cuda,vulkan --scenes bunny,mesh:1000000 --resolutions 1920x1080 \
        --photons 1000000 --frames 50 --primary-rays 2>&1 | grep -v "first image" | tee -a "$out/table.log" ;;
    sanitize-wide)
      sanitize wide scenes/bunny.json scenes/textured.glb "scenes/gem.json --spectral" ;;
    sanitize-compact)
      sanitize compact scenes/cornell.json "scenes/cornell.json --deterministic" scenes/gem.json "scenes/caustic.json --estimator knn" ;;
    pictures)
      for scene in bunny.json textured.glb smallpt.json; do
        $bin/photon-render scenes/$scene --backend cuda --width 1280 --height 960 --photons 2000000 --time 3 \
          -o "$out/picture-${scene%.*}.png" -q
        summary+=("picture $scene: exit $?")
      done ;;
    bundle-all)
      # At most 8 files come back: everything in one archive.
      (cd "$out" && tar czf /tmp/all.tgz . && find . -type f -delete && mv /tmp/all.tgz .) ;;
      bundle)
      # Only 8 files come back: everything but the pictures goes into one archive.
      (cd "$out" && tar czf /tmp/results.tgz --exclude '*.png' --exclude '*.exr' . &&
        find . -type f ! -name '*.png' -delete && mv /tmp/results.tgz .) ;;
  esac
done
printf '%s\n' "${summary[@]}"
