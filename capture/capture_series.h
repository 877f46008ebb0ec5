// A series of bracketed stacks from one camera, as `glarecam capture` takes them: `count`
// brackets, each started `interval` after the one before, each written atomically under the
// output directory as soon as it is complete (bracketer.h). A stop request (Ctrl-C, SIGTERM:
// core/interruption.h) ends the series after the stack being taken, with kInternal "interrupted
// after N of M stacks"; a capture that fails ends it with its error. What surrounds the camera on
// a rig (the operator's button, α measured before each stack and again for the bracket's middle,
// the status LED) joins through a SeriesRig; without one, every stack is taken with the settings
// as given.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>

#include "capture/bracketer.h"
#include "capture/camera.h"
#include "core/error.h"
#include "core/time.h"

namespace glarecam::capture {

class SeriesRig {
 public:
  virtual ~SeriesRig() = default;
  // Before stack `index` (from 0): waits for what the rig needs (a button press) and records the
  // rig's state in `settings` (α, the geometry block). false: stopped while waiting.
  virtual Result<bool> prepareStack(CaptureSettings& settings, std::uint64_t index) = 0;
  // After the bracket, before the stack is written.
  virtual void finishStack(CapturedStack& stack, UtcTime bracket_start, UtcTime bracket_end) = 0;
};

struct SeriesOptions {
  std::filesystem::path out;                  // the stacks' parent directory
  std::uint64_t count = 1;                    // stacks in the series, at least 1
  std::chrono::duration<double> interval{0};  // from one bracket's start to the next
  // Told each stack's path once it is written.
  std::function<void(const std::filesystem::path&)> on_written{};

  // The first problem in words (kBadInput), or nothing.
  Status validate() const;
};

// The longest --interval a series takes: a week.
inline constexpr std::chrono::hours kMaxSeriesInterval{7 * 24};

Status captureSeries(Camera& camera, CaptureSettings settings, const SeriesOptions& options,
                     SeriesRig* rig = nullptr);

}  // namespace glarecam::capture
