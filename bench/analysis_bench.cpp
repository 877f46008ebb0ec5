// Benchmarks of the glare analysis on the cached stack's merged luminance image (bench_stack.h),
// both levels the method asks for, the limit at the stack's α and half the maximum:
//  - analysis/glarecam: robust maximum, sub-pixel contours, geometric ellipse fits in the
//    angular plane, uncertainty and region counts (pipeline/glare_analysis.h);
//  - analysis/glarecam_ladder: the same with the contour ladder (every fixed level from
//    10 000 cd/m² up to the peak, sharing one flood of the image), what `process` runs;
//  - analysis/opencv_fitellipse: the usual OpenCV recipe on the same image: the plain maximum
//    (cv::minMaxLoc), then per level cv::threshold, cv::findContours (outer contours) and
//    cv::fitEllipse on the largest: a binary, pixel-biased answer in pixels, not degrees.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bench/bench_stack.h"
#include "bench/benchmarks.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/limit_curve.h"

namespace glarecam::bench {
namespace {

const calibration::MergedImage* mergedOrSkip(benchmark::State& state) {
  const Result<calibration::MergedImage>& merged = benchMergedImage();
  if (!merged) {
    state.SkipWithError(merged.error().message.c_str());
    return nullptr;
  }
  return &*merged;
}

void analysisGlarecam(benchmark::State& state, bool ladder) {
  const BenchStack* stack = benchStackOrSkip(state);
  const calibration::MergedImage* merged = stack ? mergedOrSkip(state) : nullptr;
  if (!merged) return;
  const calibration::CameraModel camera(stack->calibration.intrinsics);
  const pipeline::GlareAnalysisOptions options{
      .limit_cd_m2 = pipeline::glareLimitCdM2(stack->options.alpha_deg),
      .thresholds_cd_m2 = {},
      .ladder = ladder};
  for (auto _ : state) {
    const pipeline::LuminancePeak peak = pipeline::findLuminancePeak(*merged);
    const pipeline::GlareAnalysis analysis = pipeline::analyseGlare(*merged, camera, peak, options);
    if (!analysis.limit || !analysis.limit->ellipse || !analysis.fwhm.ellipse) {
      state.SkipWithError("analysis/glarecam: no limit or FWHM ellipse on the bench stack");
      break;
    }
    if (ladder && analysis.ladder.size() < 3) {
      state.SkipWithError("analysis/glarecam_ladder: no fixed rung on the bench stack");
      break;
    }
    benchmark::DoNotOptimize(analysis);
  }
  setStackCounters(state, *stack);
  if (ladder) {
    const pipeline::LuminancePeak peak = pipeline::findLuminancePeak(*merged);
    state.counters["rungs"] =
        static_cast<double>(pipeline::ladderLevelsCdM2(peak.value_cd_m2).size());
  }
}

cv::RotatedRect largestContourEllipse(const cv::Mat& luminance, double level) {
  cv::Mat mask;
  cv::threshold(luminance, mask, level, 255, cv::THRESH_BINARY);
  mask.convertTo(mask, CV_8U);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const std::vector<cv::Point>* largest = nullptr;
  for (const auto& contour : contours)
    if (!largest || contour.size() > largest->size()) largest = &contour;
  return largest && largest->size() >= 5 ? cv::fitEllipse(*largest) : cv::RotatedRect();
}

void analysisOpenCvFitEllipse(benchmark::State& state) {
  const BenchStack* stack = benchStackOrSkip(state);
  const calibration::MergedImage* merged = stack ? mergedOrSkip(state) : nullptr;
  if (!merged) return;
  const FloatImage& image = merged->luminance_cd_m2;
  // A header over the merged pixels (no copy; cv::Mat has no const view).
  const cv::Mat luminance(image.height(), image.width(), CV_32F, const_cast<float*>(image.data()));
  const double limit = pipeline::glareLimitCdM2(stack->options.alpha_deg).value_or(0);
  for (auto _ : state) {
    double max_value = 0;
    cv::minMaxLoc(luminance, nullptr, &max_value);
    benchmark::DoNotOptimize(largestContourEllipse(luminance, limit));
    benchmark::DoNotOptimize(largestContourEllipse(luminance, max_value / 2));
  }
  setStackCounters(state, *stack);
}

}  // namespace

std::vector<std::string> registerAnalysisBenchmarks() {
  benchmark::RegisterBenchmark(kAnalysisGlarecam, analysisGlarecam, false)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kAnalysisGlarecamLadder, analysisGlarecam, true)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kAnalysisOpenCvFitEllipse, analysisOpenCvFitEllipse)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  return {kAnalysisGlarecam, kAnalysisGlarecamLadder, kAnalysisOpenCvFitEllipse};
}

}  // namespace glarecam::bench
