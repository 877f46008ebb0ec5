// process/end_to_end/SIZE: `glarecam process` as the rig runs it: decode the stack's PNG frames,
// merge, summarise and write luminance.exr, quality.exr, luminance.png and result.json. Beside it
// process/decode_floor/SIZE: reading the same stack's manifest and decoding its frames alone, on
// the same threads: what every process pays before any merge, its floor; and
// process/no_ladder/SIZE: the same process without the contour ladder (process --no-ladder), the
// peer the ladder's price is measured against (docs/process.md: at most 10 % at 5 MP). At 1.25, 5
// and 12 MP.
// Counters: the results' bytes on disk, the stack's, and their ratio (the results are meant to be
// smaller than the measurement). Each stack is written once to the scratch directory; each
// iteration processes it into the same output directory (overwritten atomically, as on
// re-processing).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "bench/bench_stack.h"
#include "bench/benchmarks.h"
#include "core/stack_io.h"
#include "pipeline/process_stack.h"

namespace glarecam::bench {
namespace {

// Seconds per iteration (file I/O, zlib): a few are enough.
constexpr benchmark::IterationCount kEndToEndIterations = 3;

// Bytes of the regular files under `directory`.
double directoryBytes(const std::filesystem::path& directory) {
  std::uintmax_t bytes = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(directory, ec)) {
    if (entry.is_regular_file(ec)) bytes += entry.file_size(ec);
  }
  return static_cast<double>(bytes);
}

void processEndToEnd(benchmark::State& state, const SensorSize& size, bool ladder) {
  const Result<std::filesystem::path>& directory = benchStackDirectory(size);
  if (!directory) {
    state.SkipWithError(directory.error().message.c_str());
    return;
  }
  pipeline::ProcessOptions options;
  options.output_directory = scratchDirectory() / (std::string("result-") + size.name);
  options.threads = 0;  // all cores
  options.show_progress = false;
  options.ladder = ladder;
  for (auto _ : state) {
    Result<pipeline::ProcessSummary> summary = pipeline::processStack(*directory, options);
    if (!summary) {
      state.SkipWithError(summary.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(summary);
  }
  const double results = directoryBytes(*options.output_directory);
  const double stack = directoryBytes(*directory);
  state.counters["results_bytes"] = results;
  state.counters["stack_bytes"] = stack;
  state.counters["results/stack"] = stack > 0 ? results / stack : 0;
}

void decodeFloor(benchmark::State& state, const SensorSize& size) {
  const Result<std::filesystem::path>& directory = benchStackDirectory(size);
  if (!directory) {
    state.SkipWithError(directory.error().message.c_str());
    return;
  }
  StackReadOptions read_options;  // as processStack reads it: frames decoded on all cores
  read_options.threads = 0;
  for (auto _ : state) {
    Result<Stack> stack = readStack(*directory, read_options);
    if (!stack) {
      state.SkipWithError(stack.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(stack);
  }
}

std::string processEndToEndName(const SensorSize& size) {
  return std::string(kProcessEndToEnd) + "/" + size.name;
}
std::string processDecodeFloorName(const SensorSize& size) {
  return std::string(kProcessDecodeFloor) + "/" + size.name;
}
std::string processNoLadderName(const SensorSize& size) {
  return std::string(kProcessNoLadder) + "/" + size.name;
}

}  // namespace

std::vector<std::string> registerProcessBenchmarks() {
  std::vector<std::string> names;
  for (const SensorSize& size : kProcessSensorSizes) {
    benchmark::RegisterBenchmark(processDecodeFloorName(size).c_str(), decodeFloor, size)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(kEndToEndIterations);
    benchmark::RegisterBenchmark(processNoLadderName(size).c_str(), processEndToEnd, size, false)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(kEndToEndIterations);
    benchmark::RegisterBenchmark(processEndToEndName(size).c_str(), processEndToEnd, size, true)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(kEndToEndIterations);
    names.push_back(processDecodeFloorName(size));
    names.push_back(processNoLadderName(size));
    names.push_back(processEndToEndName(size));
  }
  return names;
}

}  // namespace glarecam::bench
