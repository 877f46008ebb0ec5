// Benchmarks of the HDR merge on the cached full-size stack (bench_stack.h):
//  - merge/glarecam: calibration::mergeInto, all cores, output buffers reused;
//  - merge/memory_floor: the cheapest pass that touches the same data (read every frame pixel
//    once, write one float per pixel), on the same threads: what bandwidth alone costs;
//  - merge/opencv_debevec: cv::MergeDebevec, the usual off-the-shelf HDR merge, on the same
//    stack.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>
#include <string>
#include <vector>

#include "bench/bench_stack.h"
#include "bench/benchmarks.h"
#include "calibration/hdr_merge.h"
#include "core/parallel.h"

namespace glarecam::bench {
namespace {

constexpr double kMicrosecondsPerSecond = 1.0e6;
// cv::MergeDebevec takes seconds per iteration on a 5 MP stack: two are enough.
constexpr benchmark::IterationCount kDebevecIterations = 2;

void mergeGlarecam(benchmark::State& state) {
  const BenchStack* stack = benchStackOrSkip(state);
  if (!stack) return;
  const calibration::MergeInput input = stack->mergeInput();
  const calibration::MergeOptions options;  // threads = 0: all cores
  calibration::MergedImage output;
  if (Status status = calibration::mergeInto(input, options, output);
      !status) {  // allocates the buffers
    state.SkipWithError(status.error().message.c_str());
    return;
  }
  for (auto _ : state) {
    const Status status = calibration::mergeInto(input, options, output);
    if (!status) {
      state.SkipWithError(status.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(output.luminance_cd_m2.data());
    benchmark::ClobberMemory();
  }
  setStackCounters(state, *stack);
}

// The bandwidth floor: sum of the frames' values per pixel, as float. One read of every frame
// pixel and one float written per pixel, banded over rows like the merge; the output row stays
// in L1 while the frames stream through.
void sumFrames(const std::vector<RawFrame>& frames, FloatImage& sum, unsigned threads) {
  const std::size_t width = static_cast<std::size_t>(sum.width());
  parallelRows(sum.height(), threads, [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      float* __restrict out = sum.row(y).data();
      const std::uint16_t* __restrict first = frames.front().row(y).data();
      for (std::size_t x = 0; x < width; ++x) out[x] = first[x];
      for (std::size_t f = 1; f < frames.size(); ++f) {
        const std::uint16_t* __restrict dn = frames[f].row(y).data();
        for (std::size_t x = 0; x < width; ++x) out[x] += dn[x];
      }
    }
  });
}

void mergeMemoryFloor(benchmark::State& state) {
  const BenchStack* stack = benchStackOrSkip(state);
  if (!stack) return;
  const std::vector<RawFrame>& frames = stack->simulated.frames;
  FloatImage sum(frames.front().width(), frames.front().height());
  const unsigned threads = defaultThreadCount();
  for (auto _ : state) {
    sumFrames(frames, sum, threads);
    benchmark::DoNotOptimize(sum.data());
    benchmark::ClobberMemory();
  }
  setStackCounters(state, *stack);
}

// MergeDebevec's input: MergeDebevec only accepts 8-bit images (CV_8U; its camera response and
// weights are 256-entry lookup tables), so the 12-bit frames are scaled to 8 bits and replicated
// to three channels (CV_8UC3, its usual colour input). Built once, outside the timed loop.
struct DebevecInput {
  std::vector<cv::Mat> images;
  std::vector<float> times_s;
};

DebevecInput makeDebevecInput(const BenchStack& stack) {
  DebevecInput input;
  const double to_8_bit = 255.0 / stack.options.sensor.full_scale_dn();
  for (std::size_t i = 0; i < stack.frameCount(); ++i) {
    const RawFrame& frame = stack.simulated.frames[i];
    // A header over the frame's pixels (no copy; const_cast only because cv::Mat has no const
    // view).
    const cv::Mat raw(frame.height(), frame.width(), CV_16UC1,
                      const_cast<std::uint16_t*>(frame.data()));
    cv::Mat gray, colour;
    raw.convertTo(gray, CV_8U, to_8_bit);
    cv::cvtColor(gray, colour, cv::COLOR_GRAY2BGR);
    input.images.push_back(colour);
    input.times_s.push_back(static_cast<float>(stack.simulated.manifest.frames[i].exposure_us /
                                               kMicrosecondsPerSecond));
  }
  return input;
}

void mergeOpenCvDebevec(benchmark::State& state) {
  const BenchStack* stack = benchStackOrSkip(state);
  if (!stack) return;
  static const DebevecInput input = makeDebevecInput(*stack);
  const cv::Ptr<cv::MergeDebevec> merge = cv::createMergeDebevec();
  cv::Mat hdr;
  for (auto _ : state) {
    merge->process(input.images, hdr, input.times_s);
    benchmark::DoNotOptimize(hdr.data);
    benchmark::ClobberMemory();
  }
  setStackCounters(state, *stack);
}

}  // namespace

std::vector<std::string> registerMergeBenchmarks() {
  benchmark::RegisterBenchmark(kMergeGlarecam, mergeGlarecam)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kMergeMemoryFloor, mergeMemoryFloor)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kMergeOpenCvDebevec, mergeOpenCvDebevec)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(kDebevecIterations);
  return {kMergeGlarecam, kMergeMemoryFloor, kMergeOpenCvDebevec};
}

}  // namespace glarecam::bench
