// glarecam-bench: runs the benchmarks (benchmarks.h) with Google Benchmark's usual flags, then
// prints the two ratios the merge kernel is held to, from the real times of this same run:
//   merge/opencv_debevec ÷ merge/glarecam   (target >= 40x: far faster than the off-the-shelf merge)
//   merge/glarecam ÷ merge/memory_floor     (target <= 2x: close to what the memory bandwidth allows)
// A ratio is printed only when both of its benchmarks ran (--benchmark_filter may skip some).
#include <benchmark/benchmark.h>

#include <unistd.h>  // isatty

#include <cstdio>
#include <ostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/benchmarks.h"

namespace glarecam::bench {
namespace {

constexpr double kDebevecTargetRatio = 40.0;
constexpr double kMemoryFloorTargetRatio = 2.0;

// The console reporter, plus:
//  - it records each benchmark's mean real time per iteration (seconds, over its repetitions);
//  - it prints the names as registered: Google Benchmark appends "/iterations:N" and
//    "/real_time" to the names of benchmarks set up with Iterations() and UseRealTime().
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  using ConsoleReporter::ConsoleReporter;

  void ReportRuns(const std::vector<Run>& runs) override {
    std::vector<Run> renamed = runs;
    for (Run& run : renamed) {
      run.run_name.min_time.clear();
      run.run_name.iterations.clear();
      run.run_name.time_type.clear();
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      Timing& timing = timings_[run.run_name.function_name];
      timing.total_s += run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
      ++timing.runs;
    }
    ConsoleReporter::ReportRuns(renamed);
  }

  std::optional<double> realTimeSeconds(const std::string& name) const {
    const auto it = timings_.find(name);
    if (it == timings_.end() || it->second.runs == 0) return std::nullopt;
    return it->second.total_s / it->second.runs;
  }

 private:
  struct Timing {
    double total_s = 0;
    int runs = 0;
  };
  std::map<std::string, Timing> timings_;
};

enum class Target { kAtLeast, kAtMost };

// One line "ratio A ÷ B = N.Nx (target >= Tx)", when both benchmarks ran.
void printRatio(const RecordingReporter& reporter, const std::string& numerator, const std::string& denominator,
                int decimals, Target target, double target_ratio) {
  const std::optional<double> top = reporter.realTimeSeconds(numerator);
  const std::optional<double> bottom = reporter.realTimeSeconds(denominator);
  if (!top || !bottom || !(*bottom > 0)) return;
  char line[256];
  std::snprintf(line, sizeof line, "ratio %s \u00f7 %s = %.*fx (target %s %gx)\n", numerator.c_str(), denominator.c_str(),
                decimals, *top / *bottom, target == Target::kAtLeast ? ">=" : "<=", target_ratio);
  reporter.GetOutputStream() << line << std::flush;
}

}  // namespace
}  // namespace glarecam::bench

int main(int argc, char** argv) {
  using namespace glarecam::bench;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  registerMergeBenchmarks();
  registerProcessBenchmarks();

  // A display reporter given to RunSpecifiedBenchmarks replaces the one --benchmark_format and
  // --benchmark_color would choose: tabular counters, colour on a terminal.
  const bool colour = ::isatty(STDOUT_FILENO) != 0;
  RecordingReporter reporter(colour ? benchmark::ConsoleReporter::OO_ColorTabular : benchmark::ConsoleReporter::OO_Tabular);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  printRatio(reporter, "merge/opencv_debevec", "merge/glarecam", 1, Target::kAtLeast, kDebevecTargetRatio);
  printRatio(reporter, "merge/glarecam", "merge/memory_floor", 2, Target::kAtMost, kMemoryFloorTargetRatio);
  benchmark::Shutdown();
  return 0;
}
