#include "capture/calibration_series.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <thread>

#include "capture/bracketer.h"
#include "capture/camera_registry.h"

namespace glarecam::capture {

Status CalibrationSeriesOptions::validate() const {
  if (exposures_us.empty() || exposures_us.size() > kMaxSeriesFrames)
    return badInput(fmt::format("--exposures: expected 1 to {} exposures, got {}", kMaxSeriesFrames,
                                exposures_us.size()));
  if (views < 1) return badInput("--views must be at least 1");
  if (!(view_interval_s >= 0 && view_interval_s <= 3600))
    return badInput("--view-interval must be between 0 and 3600 s");
  return {};
}

Result<std::vector<std::filesystem::path>> captureCalibrationSeries(
    const CalibrationSeriesOptions& options) {
  GLARECAM_CHECK(options.validate());
  std::unique_ptr<Camera> camera;
  GLARECAM_ASSIGN(camera, openCamera(options.camera_uri, {}));
  CaptureSettings settings;
  settings.exposures_us = options.exposures_us;
  settings.gain_db = options.gain_db;
  settings.show_progress = options.show_progress;
  std::vector<std::filesystem::path> paths;
  for (int view = 0; view < options.views; ++view) {
    if (view > 0) {
      spdlog::info("calibrate: view {} of {} in {:g} s: move the board", view + 1, options.views,
                   options.view_interval_s);
      std::this_thread::sleep_for(std::chrono::duration<double>(options.view_interval_s));
    }
    CapturedStack stack;
    GLARECAM_ASSIGN(stack, captureStack(*camera, settings));
    std::filesystem::path path;
    GLARECAM_ASSIGN(path, writeCapturedStack(options.directory, stack));
    paths.push_back(std::move(path));
  }
  return paths;
}

}  // namespace glarecam::capture
