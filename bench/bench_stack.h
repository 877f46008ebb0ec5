// The synthetic stack every benchmark works on, built once per process and cached: a simulated
// rig (capture/sim) at full sensor size, so the frames carry a real glare lobe, saturated and
// under-exposed regions, and noise, i.e. the branches the merge kernel takes on real data.
// Also a scratch directory for the benchmarks that go through files, removed at exit.
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "calibration/hdr_merge.h"
#include "calibration/radiometry.h"
#include "capture/sim/simulated_stack.h"
#include "core/error.h"

namespace glarecam::bench {

// A 5 MP machine-vision sensor (Sony IMX250 class), the rig's camera.
inline constexpr int kStackWidth = 2448;
inline constexpr int kStackHeight = 2048;
// A viewing angle whose glare lobe (about 2e6 cd/m² peak) spans the whole bracket: the shortest
// of the 6 frames exposes the peak and is mostly dark, each longer one clips more of the lobe.
inline constexpr double kStackAlphaDeg = 60.0;
inline constexpr std::uint64_t kStackSeed = 1;

struct BenchStack {
  capture::SimulationOptions options;
  capture::SimulatedStack simulated;
  Calibration calibration;  // the stack's inline calibration
  std::vector<calibration::FrameRadiometry> radiometry;

  // What pipeline::processStack hands to the merge for this stack.
  calibration::MergeInput mergeInput() const;
  std::size_t frameCount() const { return simulated.frames.size(); }
  std::size_t pixelCount() const { return simulated.frames.front().pixelCount(); }
  // Bytes of raw frame data the stack holds (16-bit containers).
  std::size_t rawBytes() const { return frameCount() * pixelCount() * sizeof(std::uint16_t); }
};

// The counters every benchmark reports, so their rates compare on the same work: the raw
// stack's bytes (SetBytesProcessed) and the merged pixels ("pixels"), per second of real time.
void setStackCounters(benchmark::State& state, const BenchStack& stack);

// The cached stack; an error when the simulation failed (reported by every benchmark).
const Result<BenchStack>& benchStack();

// The cached stack, or nullptr after reporting its error on `state` (the benchmark then skips).
const BenchStack* benchStackOrSkip(benchmark::State& state);

// The cached stack merged once (all cores), as processStack merges it.
const Result<calibration::MergedImage>& benchMergedImage();

// The cached stack written once as a recorded stack directory (PNG frames + stack.json).
const Result<std::filesystem::path>& benchStackDirectory();

// A sensor the process benchmarks run at: a 1.25 MP, the rig's 5 MP (the cached stack) and a
// 12 MP machine-vision sensor (Sony IMX253 class).
struct SensorSize {
  const char* name;  // in benchmark names: "1MP", "5MP", "12MP"
  int width, height;
};
inline constexpr SensorSize kProcessSensorSizes[] = {
    {"1MP", 1224, 1024}, {"5MP", kStackWidth, kStackHeight}, {"12MP", 4096, 3000}};

// The same scene at `size`, simulated and written once as a recorded stack directory.
const Result<std::filesystem::path>& benchStackDirectory(const SensorSize& size);

// A private directory under the system temp directory, created on first use and removed
// (with everything in it) when the process exits normally.
const std::filesystem::path& scratchDirectory();

}  // namespace glarecam::bench
