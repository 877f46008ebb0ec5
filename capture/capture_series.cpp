#include "capture/capture_series.h"

#include <fmt/format.h>

#include "core/interruption.h"

namespace glarecam::capture {

Status SeriesOptions::validate() const {
  if (count == 0) return badInput("capture: --count must be at least 1");
  if (!(interval.count() >= 0 && interval <= kMaxSeriesInterval))
    return badInput("capture: --interval must be between 0 and 604800 seconds (a week)");
  if (out.empty()) return badInput("capture: --out must not be empty");
  return {};
}

Status captureSeries(Camera& camera, CaptureSettings settings, const SeriesOptions& options,
                     SeriesRig* rig) {
  GLARECAM_CHECK(options.validate());
  stopGracefullyOnSignals();
  auto next = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < options.count; ++i) {
    sleepUntil(next);
    const auto interrupted = [&] {
      return fail(ErrorCode::kInternal,
                  fmt::format("capture: interrupted after {} of {} stacks", i, options.count));
    };
    if (stopRequested()) return interrupted();
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(options.interval);
    if (rig) {
      bool go = false;
      GLARECAM_ASSIGN(go, rig->prepareStack(settings, i));
      if (!go) return interrupted();  // stopped while waiting for the button
    }
    CapturedStack stack;
    const UtcTime bracket_start = utcNow();
    GLARECAM_ASSIGN(stack, captureStack(camera, settings));
    if (rig) rig->finishStack(stack, bracket_start, utcNow());
    std::filesystem::path written;
    GLARECAM_ASSIGN(written, writeCapturedStack(options.out, stack));
    if (options.on_written) options.on_written(written);
  }
  return {};
}

}  // namespace glarecam::capture
