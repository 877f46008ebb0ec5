// Progress over an inclinometer reading (50 samples take ≈ 3 s on an ADXL355): the one helper
// `inclinometer`, `alpha`, the flip and a capture's rig share.
#pragma once

#include <functional>
#include <utility>

#include "core/progress.h"

namespace glarecam::rig {

// Calls measure(on_sample) with a progress line "inclinometer: 12/50" on stderr.
template <typename Measure>
auto withSampleProgress(int samples, bool show, Measure&& measure) {
  Progress progress("inclinometer", samples, show);
  auto result =
      std::forward<Measure>(measure)(std::function<void()>([&progress] { progress.advance(); }));
  progress.finish();
  return result;
}

}  // namespace glarecam::rig
