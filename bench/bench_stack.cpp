#include "bench/bench_stack.h"

#include <stdlib.h>  // mkdtemp (POSIX)

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <system_error>

namespace glarecam::bench {
namespace {

constexpr const char* kScratchTemplate = "glarecam-bench-XXXXXX";

Result<BenchStack> buildStack(int width = kStackWidth, int height = kStackHeight) {
  BenchStack stack;
  stack.options.width = width;
  stack.options.height = height;
  stack.options.alpha_deg = kStackAlphaDeg;
  stack.options.seed = kStackSeed;
  GLARECAM_ASSIGN(stack.simulated, capture::simulateStack(stack.options));
  if (stack.simulated.frames.empty() || !stack.simulated.manifest.calibration) {
    return fail(ErrorCode::kInternal, "bench: the simulated stack has no frames or no calibration");
  }
  stack.calibration = *stack.simulated.manifest.calibration;
  stack.radiometry =
      calibration::frameRadiometry(stack.simulated.manifest.frames, stack.calibration);
  return stack;
}

// Owns the scratch directory; its destructor (at normal exit) removes it.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / kScratchTemplate).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::perror(("glarecam-bench: cannot create " + pattern).c_str());
      std::exit(1);
    }
    path_ = pattern;
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

calibration::MergeInput BenchStack::mergeInput() const {
  calibration::MergeInput input;
  input.frames = simulated.frames;
  input.radiometry = radiometry;
  input.black_level_dn = calibration.black_level_dn;
  input.saturation_dn = calibration.saturation_dn;
  input.flat_field = nullptr;  // simulated stacks carry no flat field
  return input;
}

void setStackCounters(benchmark::State& state, const BenchStack& stack) {
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(stack.rawBytes()));
  state.counters["pixels"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(stack.pixelCount()),
      benchmark::Counter::kIsRate);
}

const Result<BenchStack>& benchStack() {
  static const Result<BenchStack> stack = buildStack();
  return stack;
}

const BenchStack* benchStackOrSkip(benchmark::State& state) {
  const Result<BenchStack>& stack = benchStack();
  if (!stack) {
    state.SkipWithError(stack.error().message.c_str());
    return nullptr;
  }
  return &*stack;
}

const Result<calibration::MergedImage>& benchMergedImage() {
  static const Result<calibration::MergedImage> merged = []() -> Result<calibration::MergedImage> {
    const Result<BenchStack>& stack = benchStack();
    if (!stack) return std::unexpected(stack.error());
    return calibration::merge(stack->mergeInput());
  }();
  return merged;
}

const std::filesystem::path& scratchDirectory() {
  static const ScratchDirectory directory;
  return directory.path();
}

const Result<std::filesystem::path>& benchStackDirectory() {
  static const Result<std::filesystem::path> directory = []() -> Result<std::filesystem::path> {
    const Result<BenchStack>& stack = benchStack();
    if (!stack) return std::unexpected(stack.error());
    const std::filesystem::path path = scratchDirectory() / "stack";
    GLARECAM_CHECK(capture::writeSimulatedStack(path, stack->simulated));
    return path;
  }();
  return directory;
}

const Result<std::filesystem::path>& benchStackDirectory(const SensorSize& size) {
  if (size.width == kStackWidth && size.height == kStackHeight) return benchStackDirectory();
  // Benchmarks run one at a time: a plain cache, each size simulated on first use.
  static std::map<std::string, Result<std::filesystem::path>> directories;
  if (const auto found = directories.find(size.name); found != directories.end())
    return found->second;
  Result<std::filesystem::path> directory = [&]() -> Result<std::filesystem::path> {
    BenchStack stack;
    GLARECAM_ASSIGN(stack, buildStack(size.width, size.height));
    const std::filesystem::path path = scratchDirectory() / (std::string("stack-") + size.name);
    GLARECAM_CHECK(capture::writeSimulatedStack(path, stack.simulated));
    return path;
  }();
  return directories.emplace(size.name, std::move(directory)).first->second;
}

}  // namespace glarecam::bench
