// sweep/20_stacks: `glarecam sweep` over 20 simulated stacks (α 5…80°, half-size 1224x1024
// frames, as the demo writes them), once on one thread and once on every core, for the speed-up
// of processing stacks in parallel. The stacks are simulated and written once per process.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_stack.h"
#include "bench/benchmarks.h"
#include "capture/sim/simulated_stack.h"
#include "pipeline/sweep.h"

namespace glarecam::bench {
namespace {

namespace fs = std::filesystem;

constexpr int kSweepStacks = 20;
constexpr double kFirstAlphaDeg = 5.0, kLastAlphaDeg = 80.0;
constexpr int kSweepWidth = 1224, kSweepHeight = 1024;
// Seconds per iteration: two are enough.
constexpr benchmark::IterationCount kSweepIterations = 2;

const Result<fs::path>& sweepStacks() {
  static const Result<fs::path> directory = []() -> Result<fs::path> {
    const fs::path root = scratchDirectory() / "sweep-stacks";
    for (int i = 0; i < kSweepStacks; ++i) {
      capture::SimulationOptions options;
      options.alpha_deg =
          kFirstAlphaDeg + (kLastAlphaDeg - kFirstAlphaDeg) * i / (kSweepStacks - 1);
      options.width = kSweepWidth;
      options.height = kSweepHeight;
      options.seed = i + 1;
      auto stack = capture::simulateStack(options);
      if (!stack) return std::unexpected(stack.error());
      GLARECAM_CHECK(capture::writeSimulatedStack(root / ("stack-" + std::to_string(i)), *stack));
    }
    return root;
  }();
  return directory;
}

void sweepStacksWith(benchmark::State& state, unsigned threads) {
  const Result<fs::path>& root = sweepStacks();
  if (!root) {
    state.SkipWithError(root.error().message.c_str());
    return;
  }
  const pipeline::StackSearch search = pipeline::findStacks({*root});
  pipeline::SweepOptions options;
  options.output_directory = scratchDirectory() / "sweep-out";
  options.threads = threads;
  options.show_progress = false;
  for (auto _ : state) {
    auto summary = pipeline::runSweep(search, options);
    if (!summary) {
      state.SkipWithError(summary.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(summary);
  }
  state.counters["stacks/s"] = benchmark::Counter(static_cast<double>(kSweepStacks),
                                                  benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

std::vector<std::string> registerSweepBenchmarks() {
  for (const auto& [name, threads] :
       {std::pair{kSweepOneThread, 1u}, std::pair{kSweepAllThreads, 0u}}) {
    benchmark::RegisterBenchmark(
        name, [threads = threads](benchmark::State& state) { sweepStacksWith(state, threads); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(kSweepIterations);
  }
  return {kSweepOneThread, kSweepAllThreads};
}

}  // namespace glarecam::bench
