#include "capture/camera.h"

#include <fmt/format.h>

#include <cmath>

namespace glarecam::capture {

namespace {

// "aravis:GV01: message", unless the backend named the camera already.
Error namingCamera(Error error, const std::string& uri) {
  if (error.message.starts_with(uri + ": ")) return error;
  return withContext(std::move(error), uri);
}

}  // namespace

double bracketFloorS(std::span<const ExposureRequest> requests, double frame_bytes,
                     double link_bytes_per_s) {
  double seconds = 0;
  for (const ExposureRequest& request : requests)
    seconds += request.exposure_us / 1e6 + frame_bytes / link_bytes_per_s;
  return seconds;
}

Status checkRequest(const ExposureRequest& request, const CameraLimits& limits,
                    std::string_view uri) {
  const double exposure_us = request.exposure_us;
  if (!(std::isfinite(exposure_us) && exposure_us > 0 && exposure_us >= limits.min_exposure_us &&
        (limits.max_exposure_us <= 0 || exposure_us <= limits.max_exposure_us)))
    return badInput(fmt::format("{}: exposure {:g} µs is outside the camera's {:g} … {:g} µs", uri,
                                exposure_us, limits.min_exposure_us, limits.max_exposure_us));
  const double gain_db = request.gain_db;
  if (!(std::isfinite(gain_db) && gain_db >= limits.min_gain_db && gain_db <= limits.max_gain_db)) {
    if (limits.min_gain_db == 0 && limits.max_gain_db == 0)
      return badInput(fmt::format("{}: gain {:g} dB requested, but the camera has no analogue gain",
                                  uri, gain_db));
    return badInput(fmt::format("{}: gain {:g} dB is outside the camera's {:g} … {:g} dB", uri,
                                gain_db, limits.min_gain_db, limits.max_gain_db));
  }
  return {};
}

Result<std::vector<CapturedFrame>> Camera::capture(std::span<const ExposureRequest> requests) {
  const std::string& uri = info().uri;
  if (requests.empty()) return std::vector<CapturedFrame>{};
  const CameraLimits range = limits();
  for (const ExposureRequest& request : requests) GLARECAM_CHECK(checkRequest(request, range, uri));
  Result<std::vector<CapturedFrame>> frames = catchExceptions([&] { return doCapture(requests); });
  if (!frames) return std::unexpected(namingCamera(std::move(frames.error()), uri));
  if (frames->size() != requests.size())
    return fail(ErrorCode::kInternal,
                fmt::format("{}: {} frames for {} requests", uri, frames->size(), requests.size()));
  return frames;
}

}  // namespace glarecam::capture
