// Benchmarks of the BRDF route (docs/brdf.md) on one angle of incidence of the standard surface
// as the simulated goniophotometer measures it (α 30°, about 11 700 samples, 1 % noise):
//  - brdf/angle: what `glarecam brdf` does for it before writing files: the sampling check and
//    Gaussian fit, the triangulation and interpolation, the sun's disc, the 801-pixel picture,
//    the robust peak and the glare analysis with the ladder;
//  - brdf/analysis_floor: the peak and the glare analysis alone on that picture, the camera
//    route's share, which any route pays.
// Their ratio is what reading a goniophotometer costs beyond the analysis.
#include <benchmark/benchmark.h>

#include <optional>
#include <string>
#include <vector>

#include "bench/benchmarks.h"
#include "brdf/brdf_luminance.h"
#include "brdf/simulated_goniophotometer.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/limit_curve.h"
#include "pipeline/luminance_stats.h"
#include "surface/surface_catalogue.h"

namespace glarecam::bench {
namespace {

constexpr double kBrdfAlphaDeg = 30;

const brdf::BrdfMeasurement& benchMeasurement() {
  static const brdf::BrdfMeasurement measurement = [] {
    const surface::MicrofacetBrdf model(surface::standardSurface());
    return brdf::simulateMeasurement(model, kBrdfAlphaDeg, brdf::GoniophotometerOptions{},
                                     "bench.dat");
  }();
  return measurement;
}

pipeline::GlareAnalysis analyse(const calibration::MergedImage& image,
                                const calibration::CameraModel& camera) {
  const pipeline::LuminanceStats stats = pipeline::luminanceStats(image);
  return pipeline::analyseGlare(image, camera, stats.max,
                                {.limit_cd_m2 = pipeline::glareLimitCdM2(kBrdfAlphaDeg),
                                 .thresholds_cd_m2 = {},
                                 .scale_relative_uncertainty = 0,
                                 .ladder = true});
}

// What `glarecam brdf` computes of a measurement before the analysis: the sampling check and
// the picture under the sun.
Result<brdf::BrdfLuminance> picture(const brdf::BrdfMeasurement& m) {
  brdf::SamplingCheck sampling;
  GLARECAM_ASSIGN(sampling, brdf::checkSampling(m));
  return brdf::luminanceUnderSun(m, sampling);
}

void brdfAngle(benchmark::State& state) {
  const brdf::BrdfMeasurement& m = benchMeasurement();
  for (auto _ : state) {
    const auto picture = bench::picture(m);
    if (!picture) {
      state.SkipWithError(picture.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(
        analyse(picture->image, calibration::CameraModel(picture->intrinsics)));
  }
  state.counters["samples"] = static_cast<double>(m.samples.size());
}

void brdfAnalysisFloor(benchmark::State& state) {
  const brdf::BrdfMeasurement& m = benchMeasurement();
  const auto picture = bench::picture(m);
  if (!picture) {
    state.SkipWithError(picture.error().message.c_str());
    return;
  }
  const calibration::CameraModel camera(picture->intrinsics);
  for (auto _ : state) benchmark::DoNotOptimize(analyse(picture->image, camera));
  state.counters["pixels"] = static_cast<double>(picture->image.luminance_cd_m2.width()) *
                             picture->image.luminance_cd_m2.height();
}

}  // namespace

std::vector<std::string> registerBrdfBenchmarks() {
  benchmark::RegisterBenchmark(kBrdfAngle, brdfAngle)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark(kBrdfAnalysisFloor, brdfAnalysisFloor)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  return {kBrdfAngle, kBrdfAnalysisFloor};
}

}  // namespace glarecam::bench
