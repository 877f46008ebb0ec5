// process/end_to_end: `glarecam process` as the rig runs it: decode the stack's PNG frames,
// merge, summarise and write luminance.exr, quality.exr, luminance.png and result.json. The
// cached stack is written once to the scratch directory; each iteration processes it into the
// same output directory (overwritten atomically, as on re-processing).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_stack.h"
#include "bench/benchmarks.h"
#include "pipeline/process_stack.h"

namespace glarecam::bench {
namespace {

// Seconds per iteration (file I/O, zlib): a few are enough.
constexpr benchmark::IterationCount kEndToEndIterations = 3;

void processEndToEnd(benchmark::State& state) {
  const Result<std::filesystem::path>& directory = benchStackDirectory();
  if (!directory) {
    state.SkipWithError(directory.error().message.c_str());
    return;
  }
  pipeline::ProcessOptions options;
  options.output_directory = scratchDirectory() / "result";
  options.threads = 0;  // all cores
  options.show_progress = false;
  for (auto _ : state) {
    Result<pipeline::ProcessSummary> summary = pipeline::processStack(*directory, options);
    if (!summary) {
      state.SkipWithError(summary.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(summary);
  }
  setStackCounters(state, *benchStack());
}

}  // namespace

std::vector<std::string> registerProcessBenchmarks() {
  benchmark::RegisterBenchmark(kProcessEndToEnd, processEndToEnd)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(kEndToEndIterations);
  return {kProcessEndToEnd};
}

}  // namespace glarecam::bench
