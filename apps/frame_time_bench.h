// photon-bench's timing table: frame and per-stage times over backends × scenes × cases (every
// resolution × photon count × --vary value, or --grid-sweep's counts). Times are the backends'
// own stage timers, medians over timed frames after warm-up frames; the rows are printed and
// written as JSON and CSV for tools/plot_bench.py.
#pragma once

#include <chrono>

#include "apps/bench_cases.h"
#include "apps/bench_options.h"

namespace photon {

// Measures every case of every scene on every backend of `options`, printing a row for each, and
// the time from `processStart` to the first image.
void benchFrameTimes(const BenchOptions& options, const CaseLists& lists,
                     std::chrono::steady_clock::time_point processStart);

}  // namespace photon
