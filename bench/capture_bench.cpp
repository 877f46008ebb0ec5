// capture/fake_gv_bracket: a 6-frame bracket through the Aravis backend from the GigE Vision
// fake camera on loopback (640x512 Mono16, frames rendered once and reused, so the simulator is
// not what is timed), beside capture/link_floor: what any camera needs for the same bracket,
// the sum of the exposure times plus each frame's transfer at Gigabit Ethernet's rate.
// The fake camera takes each exposure before it sends the frame, as a camera does, so
// bracket ÷ floor is 1 plus the backend's overhead (triggering, buffer handling, the loopback
// transfer against Gigabit's): target <= 1.1, at most 10 % above what the camera itself needs.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench/benchmarks.h"
#include "capture/aravis/fake_gv_camera.h"
#include "capture/camera_registry.h"

namespace glarecam::bench {
namespace {

constexpr double kBytesPerPixel = 2;  // Mono16
// Half-decade steps from 100 µs: a bracket of a bright glare lobe, six frames as in the paper.
const std::vector<double> kBracketUs{100, 316, 1000, 3162, 10000, 31623};

std::vector<capture::ExposureRequest> bracketRequests() {
  std::vector<capture::ExposureRequest> requests;
  for (const double exposure : kBracketUs) requests.push_back({exposure, 0});
  return requests;
}

double linkFloorS() {
  const capture::SimulationOptions scene = capture::fakeCameraScene();
  return capture::bracketFloorS(bracketRequests(), scene.width * scene.height * kBytesPerPixel);
}

void fakeGvBracket(benchmark::State& state) {
  capture::FakeGvCameraOptions fake_options;  // the default scene: 640x512
  fake_options.reuse_frames = true;
  auto fake = capture::FakeGvCamera::start(fake_options);
  if (!fake) {
    state.SkipWithError(fake.error().message.c_str());
    return;
  }
  auto camera = capture::openCamera((*fake)->uri(), {});
  if (!camera) {
    state.SkipWithError(camera.error().message.c_str());
    return;
  }
  const std::vector<capture::ExposureRequest> requests = bracketRequests();
  (void)(*camera)->capture(requests);  // warm-up: every frame rendered once
  for (auto _ : state) {
    auto frames = (*camera)->capture(requests);
    if (!frames) {
      state.SkipWithError(frames.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(frames);
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(kBracketUs.size()),
                                                  benchmark::Counter::kIsIterationInvariantRate);
}

void linkFloor(benchmark::State& state) {
  for (auto _ : state) state.SetIterationTime(linkFloorS());
}

}  // namespace

std::vector<std::string> registerCaptureBenchmarks() {
  benchmark::RegisterBenchmark(kCaptureFakeGvBracket, fakeGvBracket)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond)
      ->MinTime(2.0);
  benchmark::RegisterBenchmark(kCaptureLinkFloor, linkFloor)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  return {kCaptureFakeGvBracket, kCaptureLinkFloor};
}

}  // namespace glarecam::bench
