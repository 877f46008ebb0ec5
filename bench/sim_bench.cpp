// Benchmarks of the simulated camera's scene at the rig's size (1224×1024, 40° across, α 30°), what
// every simulated stack, the demo's sweep and the route check wait for before the sensor:
//  - sim/surface_scene: the standard surface under the sun's disc (capture/sim/surface_scene.h):
//    the point-source grid over the frame, its disc convolution, the bicubic picture, and the
//    truth from the surface's own contours (peak, limit and half maximum by bisection);
//  - sim/curves_scene: the standard module's empirical-curve lobe, the scene it replaces as the
//    truth of the physical routes (its closed-form Gaussian is the floor any scene pays: the
//    rays of every pixel).
// Their ratio is the price of drawing the scene from a physical surface.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench/benchmarks.h"
#include "capture/sim/simulated_stack.h"

namespace glarecam::bench {
namespace {

constexpr double kSceneAlphaDeg = 30;

void sceneBenchmark(benchmark::State& state, const char* surface) {
  capture::SimulationOptions options;
  options.alpha_deg = kSceneAlphaDeg;
  options.surface = surface;
  for (auto _ : state) {
    auto scene = capture::renderSimulatedScene(options);
    if (!scene) {
      state.SkipWithError(scene.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(scene->truth.peak_cd_m2);
  }
  state.counters["pixels"] = static_cast<double>(options.width) * options.height;
}

}  // namespace

std::vector<std::string> registerSimBenchmarks() {
  benchmark::RegisterBenchmark(kSimSurfaceScene, sceneBenchmark, "standard")
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(kSimCurvesScene, sceneBenchmark, "curves:standard")
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  return {kSimSurfaceScene, kSimCurvesScene};
}

}  // namespace glarecam::bench
