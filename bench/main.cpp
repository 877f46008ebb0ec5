// glarecam-bench: runs the benchmarks (benchmarks.h) with Google Benchmark's usual flags, then
// prints the ratios the kernels are held to, from the real times of this same run:
//   merge/opencv_debevec ÷ merge/glarecam        target >= 40x: far faster than the usual merge
//   merge/glarecam ÷ merge/memory_floor          target <= 3x: close to memory bandwidth
//   analysis/glarecam ÷ merge/glarecam           target <= 3x: analysis no bottleneck
//   analysis/glarecam ÷ analysis/opencv_fitellipse   (no target: the price of sub-pixel
//                                                      contours, angles and uncertainties)
//   analysis/glarecam_ladder ÷ analysis/glarecam (no target: the contour ladder's rungs against
//                                                the method's two levels alone)
//   process/end_to_end/SIZE ÷ process/decode_floor/SIZE  target <= 1.5x at 5 MP: a whole
//                                                process near the price of decoding its frames
//   process/end_to_end/SIZE ÷ process/no_ladder/SIZE     target <= 1.1x at 5 MP: the contour
//                                                ladder costs process at most 10 %
//   capture/fake_gv_bracket ÷ capture/link_floor target <= 1.1x: the capture's overhead at
//                                                most 10 % of exposure plus transfer (the fake
//                                                camera takes its exposures)
//   sun/glarecam_spa ÷ sun/libnova               (no target: the price of SPA's accuracy, 0.0003°
//                                                against libnova's 0.07°)
//   hazard/year ÷ sun/year_spa                   target <= 1.5x: a year's glare for one array
//                                                and observer near the cost of its sun alone
//   per extra array–observer pair ÷ sun/year_spa target <= 0.1x: (hazard/scene − hazard/year)
//                                                ÷ (pairs − 1), the sun shared by every pair
//   hazard/year_clear_sky ÷ hazard/year           target <= 1.3x: the sun's own brightness
//   hazard/year_obstructions ÷ hazard/year        target <= 2x: with 5 buildings clipped
//   brdf/angle ÷ brdf/analysis_floor             (no target yet: what reading a goniophotometer
//                                                file costs beyond the glare analysis)
//   sim/surface_scene ÷ sim/curves_scene         (no target: the price of drawing the simulated
//                                                camera's scene from a physical surface)
// A ratio is printed only when both of its benchmarks ran (--benchmark_filter may skip some).
// Google Benchmark's flags work as in any benchmark binary: --benchmark_format=console|json|csv
// chooses the report on stdout (the ratio lines then go to stderr, so stdout stays one JSON
// document or one CSV table), --benchmark_out=FILE --benchmark_out_format=... writes a file too,
// --benchmark_color the console's colours.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bench/bench_stack.h"
#include "bench/benchmarks.h"
#include "core/build_config.h"
#include "core/logging.h"
#include "core/memory.h"

namespace glarecam::bench {
namespace {

constexpr double kDebevecTargetRatio = 40.0;
constexpr double kDecodeFloorTargetRatio = 1.5;  // at 5 MP, the rig's sensor
// The merge reads six 16-bit frames and writes ten bytes a pixel (luminance,
// uncertainty, count, flag) against the floor's four; 3 leaves the arithmetic one more pass.
constexpr double kMemoryFloorTargetRatio = 3.0;
constexpr double kAnalysisTargetRatio = 3.0;
constexpr double kLadderTargetRatio = 1.1;  // at 5 MP
constexpr double kCaptureOverheadTargetRatio = 1.1;
constexpr double kHazardTargetRatio = 1.5;
constexpr double kHazardPairTargetRatio = 0.1;
constexpr double kHazardScenePairs = 10 * 20;  // hazard/scene's arrays × observers
// The sun's own brightness (the contour ladder at every step) and 5 obstructions (issue 39).
constexpr double kHazardClearSkyTargetRatio = 1.3;
constexpr double kHazardObstructionsTargetRatio = 2.0;
// Issue 40: a pair that never glares costs at most a fiftieth of one that glares.
constexpr double kNeverGlaringTargetRatio = 1.0 / 50;
// Room after a name for an aggregate's suffix ("_median", "_stddev") with --benchmark_repetitions.
constexpr std::size_t kAggregateSuffixWidth = 7;

// Passes every report on to the reporter Google Benchmark's flags chose, and records each
// benchmark's mean real time per iteration (seconds, over repetitions, or the "mean" aggregate
// with --benchmark_report_aggregates_only) for the ratios. On the console it also prints the
// names as registered: Google Benchmark appends "/iterations:N" and "/real_time" to the names of
// benchmarks set up with Iterations() and UseRealTime(), and sizes the name column for them.
class RecordingReporter : public benchmark::BenchmarkReporter {
 public:
  RecordingReporter(benchmark::BenchmarkReporter& display, bool console, std::size_t longest_name)
      : display_(display), console_(console), name_width_(longest_name + kAggregateSuffixWidth) {}

  bool ReportContext(const Context& context) override {
    if (!console_) return display_.ReportContext(context);
    Context sized = context;
    sized.name_field_width = std::min(context.name_field_width, name_width_);
    return display_.ReportContext(sized);
  }

  void ReportRuns(const std::vector<Run>& runs) override {
    std::vector<Run> renamed = runs;
    for (Run& run : renamed) {
      if (console_) {
        run.run_name.min_time.clear();
        run.run_name.iterations.clear();
        run.run_name.time_type.clear();
      }
      if (run.error_occurred) continue;
      const double seconds =
          run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
      Timing& timing = timings_[run.run_name.function_name];
      if (run.run_type == Run::RT_Iteration) {
        timing.total_s += seconds;
        ++timing.runs;
      } else if (run.aggregate_name == "mean") {  // --benchmark_report_aggregates_only
        timing.mean_s = seconds;
      }
    }
    display_.ReportRuns(renamed);
  }

  void Finalize() override { display_.Finalize(); }

  // Where the ratio lines go: under the console's table, or stderr beside a JSON or CSV report.
  std::ostream& ratioStream() const { return console_ ? display_.GetOutputStream() : std::cerr; }

  std::optional<double> realTimeSeconds(const std::string& name) const {
    const auto it = timings_.find(name);
    if (it == timings_.end()) return std::nullopt;
    if (it->second.runs > 0) return it->second.total_s / it->second.runs;
    return it->second.mean_s;
  }

 private:
  struct Timing {
    double total_s = 0;
    int runs = 0;
    std::optional<double> mean_s;  // the "mean" aggregate, when only aggregates are reported
  };
  benchmark::BenchmarkReporter& display_;
  bool console_;
  std::size_t name_width_;
  std::map<std::string, Timing> timings_;
};

enum class Target { kAtLeast, kAtMost, kNone };

// One line "ratio A ÷ B = N.Nx (target >= Tx)", when both benchmarks ran.
void printRatio(const RecordingReporter& reporter, const std::string& numerator,
                const std::string& denominator, int decimals, Target target, double target_ratio) {
  const std::optional<double> top = reporter.realTimeSeconds(numerator);
  const std::optional<double> bottom = reporter.realTimeSeconds(denominator);
  if (!top || !bottom || !(*bottom > 0)) return;
  char target_text[64] = "";
  if (target != Target::kNone) {
    std::snprintf(target_text, sizeof target_text, " (target %s %gx)",
                  target == Target::kAtLeast ? ">=" : "<=", target_ratio);
  }
  char line[256];
  std::snprintf(line, sizeof line, "ratio %s \u00f7 %s = %.*fx%s\n", numerator.c_str(),
                denominator.c_str(), decimals, *top / *bottom, target_text);
  reporter.ratioStream() << line << std::flush;
}

// What each array–observer pair beyond the first adds to a year, as a fraction of the sun pass.
void printPairRatio(const RecordingReporter& reporter) {
  const std::optional<double> scene = reporter.realTimeSeconds(kHazardScene);
  const std::optional<double> year = reporter.realTimeSeconds(kHazardYear);
  const std::optional<double> sun = reporter.realTimeSeconds(kSunYearSpa);
  if (!scene || !year || !sun || !(*sun > 0)) return;
  char line[256];
  std::snprintf(line, sizeof line,
                "ratio (%s \u2212 %s) \u00f7 %.0f extra pairs \u00f7 %s = %.3fx (target <= %gx)\n",
                kHazardScene, kHazardYear, kHazardScenePairs - 1, kSunYearSpa,
                (*scene - *year) / (kHazardScenePairs - 1) / *sun, kHazardPairTargetRatio);
  reporter.ratioStream() << line << std::flush;
}

// Pairs that never glare against pairs that glare, each less the year's sun both pay
// (hazard/pairs/none): target <= 1/50.
void printNeverGlaringRatio(const RecordingReporter& reporter) {
  const std::optional<double> none = reporter.realTimeSeconds(kHazardPairsNone);
  const std::optional<double> never = reporter.realTimeSeconds(kHazardPairsNever);
  const std::optional<double> glaring = reporter.realTimeSeconds(kHazardPairsGlaring);
  if (!none || !never || !glaring || !(*glaring > *none)) return;
  char line[256];
  std::snprintf(line, sizeof line,
                "ratio (%s \u2212 %s) \u00f7 (%s \u2212 %s) = %.4fx (target <= %gx)\n",
                kHazardPairsNever, kHazardPairsNone, kHazardPairsGlaring, kHazardPairsNone,
                std::max(0.0, *never - *none) / (*glaring - *none), kNeverGlaringTargetRatio);
  reporter.ratioStream() << line << std::flush;
}

// Google Benchmark's CSV reporter writes its header from the first benchmark's counters and
// aborts when a later one has another ("All counters must be present in each run"), and
// glarecam's benchmarks each have counters of their own. This one hands it every run at once,
// at the end: the header then names every counter, and a run without one leaves its cell empty.
class CsvReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context& context) override {
    csv_.SetOutputStream(&GetOutputStream());  // set by the library: stdout, or --benchmark_out
    csv_.SetErrorStream(&GetErrorStream());
    return csv_.ReportContext(context);
  }
  void ReportRuns(const std::vector<Run>& runs) override {
    runs_.insert(runs_.end(), runs.begin(), runs.end());
  }
  void Finalize() override {
    if (!runs_.empty()) csv_.ReportRuns(runs_);
    csv_.Finalize();
  }

 private:
// The library's own CSV reporter, deprecated in 1.7 (to be removed) but what --benchmark_format=csv
// gives; this wrapper goes when it does.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  benchmark::CSVReporter csv_;
#pragma GCC diagnostic pop
  std::vector<Run> runs_;
};

// The report formats the command line asks for (Google Benchmark's flags, read before it parses
// them: it exits 1 on an unknown format, glarecam's commands 2).
struct ReportFormats {
  std::string display = "console";  // --benchmark_format
  std::string file = "json";        // --benchmark_out_format
  bool to_file = false;             // --benchmark_out=FILE given
};

std::optional<ReportFormats> reportFormats(int argc, char** argv) {
  ReportFormats formats;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    for (const auto& [flag, format] :
         {std::pair<std::string_view, std::string*>{"--benchmark_format=", &formats.display},
          {"--benchmark_out_format=", &formats.file}}) {
      if (!arg.starts_with(flag)) continue;
      *format = arg.substr(flag.size());
      if (*format != "console" && *format != "json" && *format != "csv") {
        std::fprintf(stderr, "glarecam-bench: %s: expected console, json or csv\n", argv[i]);
        return std::nullopt;
      }
    }
    formats.to_file |= arg.starts_with("--benchmark_out=");
  }
  return formats;
}

}  // namespace
}  // namespace glarecam::bench

int main(int argc, char** argv) {
  using namespace glarecam::bench;
  const std::optional<ReportFormats> formats = reportFormats(argc, argv);
  if (!formats) return 2;
  glarecam::reuseLargeAllocations();                    // as glarecam and glarecamd run
  glarecam::initLogging(glarecam::Verbosity::kNormal);  // as glarecam: warnings and errors only
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  std::vector<std::string> names = registerMergeBenchmarks();
  for (std::string& name : registerAnalysisBenchmarks()) names.push_back(std::move(name));
  for (std::string& name : registerProcessBenchmarks()) names.push_back(std::move(name));
  for (std::string& name : registerSweepBenchmarks()) names.push_back(std::move(name));
#if GLARECAM_WITH_ARAVIS
  for (std::string& name : registerCaptureBenchmarks()) names.push_back(std::move(name));
#endif
#if GLARECAM_WITH_LIBNOVA
  for (std::string& name : registerSunBenchmarks()) names.push_back(std::move(name));
#endif
  for (std::string& name : registerHazardBenchmarks()) names.push_back(std::move(name));
  for (std::string& name : registerBrdfBenchmarks()) names.push_back(std::move(name));
  for (std::string& name : registerSimBenchmarks()) names.push_back(std::move(name));
  std::size_t longest_name = 0;
  for (const std::string& name : names) longest_name = std::max(longest_name, name.size());

  // The display reporter --benchmark_format chose (the library's, CSV through CsvReporter), and
  // the file's: the library makes it unless it is CSV.
  CsvReporter csv_display, csv_file;
  benchmark::BenchmarkReporter& display =
      formats->display == "csv" ? csv_display : *benchmark::CreateDefaultDisplayReporter();
  RecordingReporter reporter(display, formats->display == "console", longest_name);
  benchmark::RunSpecifiedBenchmarks(
      &reporter, formats->to_file && formats->file == "csv" ? &csv_file : nullptr);
  printRatio(reporter, kMergeOpenCvDebevec, kMergeGlarecam, 1, Target::kAtLeast,
             kDebevecTargetRatio);
  printRatio(reporter, kMergeGlarecam, kMergeMemoryFloor, 2, Target::kAtMost,
             kMemoryFloorTargetRatio);
  printRatio(reporter, kAnalysisGlarecam, kMergeGlarecam, 2, Target::kAtMost, kAnalysisTargetRatio);
  printRatio(reporter, kAnalysisGlarecam, kAnalysisOpenCvFitEllipse, 2, Target::kNone, 0);
  printRatio(reporter, kAnalysisGlarecamLadder, kAnalysisGlarecam, 2, Target::kNone, 0);
  for (const SensorSize& size : kProcessSensorSizes) {
    const bool rig = size.width == kStackWidth && size.height == kStackHeight;
    printRatio(reporter, std::string(kProcessEndToEnd) + "/" + size.name,
               std::string(kProcessDecodeFloor) + "/" + size.name, 2,
               rig ? Target::kAtMost : Target::kNone, kDecodeFloorTargetRatio);
    printRatio(reporter, std::string(kProcessEndToEnd) + "/" + size.name,
               std::string(kProcessNoLadder) + "/" + size.name, 3,
               rig ? Target::kAtMost : Target::kNone, kLadderTargetRatio);
  }
  // The sweep's speed-up from parallel stacks: 1 thread ÷ all threads.
  printRatio(reporter, kSweepOneThread, kSweepAllThreads, 2, Target::kNone, 0);
  printRatio(reporter, kCaptureFakeGvBracket, kCaptureLinkFloor, 3, Target::kAtMost,
             kCaptureOverheadTargetRatio);
  printRatio(reporter, kSunGlarecamSpa, kSunLibnova, 2, Target::kNone, 0);
  printRatio(reporter, kHazardYear, kSunYearSpa, 2, Target::kAtMost, kHazardTargetRatio);
  printPairRatio(reporter);
  printNeverGlaringRatio(reporter);
  // The district's time per candidate pair at three sizes: linear when these stay near 1.
  for (std::size_t i = 1; i < std::size(kHazardCityRoofs); ++i)
    printRatio(reporter,
               std::string(kHazardCity) + "/" + std::to_string(kHazardCityRoofs[i]) + "_roofs",
               std::string(kHazardCity) + "/" + std::to_string(kHazardCityRoofs[0]) + "_roofs", 2,
               Target::kNone, 0);
  printRatio(reporter, kHazardYearClearSky, kHazardYear, 2, Target::kAtMost,
             kHazardClearSkyTargetRatio);
  printRatio(reporter, kHazardYearObstructions, kHazardYear, 2, Target::kAtMost,
             kHazardObstructionsTargetRatio);
  printRatio(reporter, kBrdfAngle, kBrdfAnalysisFloor, 2, Target::kNone, 0);
  printRatio(reporter, kSimSurfaceScene, kSimCurvesScene, 2, Target::kNone, 0);
  benchmark::Shutdown();
  return 0;
}
