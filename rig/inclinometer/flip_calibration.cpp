#include "rig/inclinometer/flip_calibration.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "core/json.h"
#include "core/time.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/sample_progress.h"
#include "rig/inclinometer/zero_offset_file.h"

namespace glarecam::rig {

namespace {

Result<FlipReading> readSavedReading(const std::filesystem::path& path) {
  FlipReading flip;
  GLARECAM_ASSIGN(flip.record, readJsonFile(path.string()));
  GLARECAM_ASSIGN(flip.reading, parseTiltReading(flip.record, path.string()));
  const auto uri = flip.record.find("uri");
  if (uri != flip.record.end() && uri->is_string()) flip.uri = uri->get<std::string>();
  return flip;
}

Result<FlipReading> takeFlipReading(Inclinometer& sensor, const std::string& uri,
                                    const TiltOptions& options, bool show_progress) {
  FlipReading flip;
  GLARECAM_ASSIGN(flip.reading, withSampleProgress(options.samples, show_progress,
                                                   [&](const std::function<void()>& on_sample) {
                                                     return measureTilt(sensor, options, {},
                                                                        on_sample);
                                                   }));
  flip.uri = uri;
  flip.record = tiltReadingJson(flip.reading);
  flip.record["uri"] = uri;
  flip.record["time"] = formatIsoTime(utcNow());
  return flip;
}

}  // namespace

Result<FlipReadings> savedFlipReadings(const std::filesystem::path& first_path,
                                       const std::filesystem::path& second_path) {
  std::error_code ec;
  if (std::filesystem::equivalent(first_path, second_path, ec))
    return badInput("inclinometer flip: --from names the same reading twice (" +
                    first_path.string() + ")");
  FlipReading first, second;
  GLARECAM_ASSIGN(first, readSavedReading(first_path));
  GLARECAM_ASSIGN(second, readSavedReading(second_path));
  if (first.record == second.record)
    return badInput(fmt::format("inclinometer flip: {} and {} hold the same reading",
                                first_path.string(), second_path.string()));
  if (!first.uri.empty() && !second.uri.empty() && !sameInclinometer(first.uri, second.uri))
    spdlog::warn("inclinometer flip: the readings name different sensors ({} and {})", first.uri,
                 second.uri);
  return FlipReadings{std::move(first), std::move(second)};
}

Result<FlipReadings> takeFlipReadings(Inclinometer& sensor, const std::string& uri,
                                      const TiltOptions& options,
                                      const std::function<Status(const TiltReading& first)>& turn,
                                      bool show_progress) {
  FlipReading first, second;
  GLARECAM_ASSIGN(first, takeFlipReading(sensor, uri, options, show_progress));
  GLARECAM_CHECK(checkNearLevel(first.reading));
  GLARECAM_CHECK(turn(first.reading));
  GLARECAM_ASSIGN(second, takeFlipReading(sensor, uri, options, show_progress));
  return FlipReadings{std::move(first), std::move(second)};
}

Status checkNearLevel(const TiltReading& reading) {
  const double worst = std::max(std::abs(reading.raw_tilt.x_deg), std::abs(reading.raw_tilt.y_deg));
  if (worst <= kMaxPlausibleZeroOffsetDeg) return {};
  return badInput(fmt::format(
      "inclinometer flip: the sensor reads tilt x {:.2f}°, y {:.2f}°; the flip needs a surface "
      "within a few degrees of level (at most {:g}°)",
      reading.raw_tilt.x_deg, reading.raw_tilt.y_deg, kMaxPlausibleZeroOffsetDeg));
}

Result<FlipCalibration> storeFlipCalibration(const std::filesystem::path& calibration_file,
                                             const FlipReadings& readings,
                                             const std::string& configured_uri) {
  const TiltReading& first = readings.first.reading;
  const TiltReading& second = readings.second.reading;
  GLARECAM_CHECK(checkNearLevel(first));
  GLARECAM_CHECK(checkNearLevel(second));
  FlipCalibration flip;
  flip.surface_x_deg = (first.raw_tilt.x_deg - second.raw_tilt.x_deg) / 2;
  flip.surface_y_deg = (first.raw_tilt.y_deg - second.raw_tilt.y_deg) / 2;
  if (std::abs(flip.surface_x_deg) < kMinFlipSurfaceTiltDeg &&
      std::abs(flip.surface_y_deg) < kMinFlipSurfaceTiltDeg)
    return badInput(fmt::format(
        "inclinometer flip: the two readings agree (surface tilt x {:.3f}°, y {:.3f}°): the frame "
        "was not turned, or the surface is level, where a turn does not show; turn it 180° on a "
        "surface tilted at least {:g}° (a shim under one side)",
        flip.surface_x_deg, flip.surface_y_deg, kMinFlipSurfaceTiltDeg));
  flip.zero = flipZeroOffset(first, second);
  if (std::abs(flip.zero.offset.x_deg) > kMaxPlausibleZeroOffsetDeg ||
      std::abs(flip.zero.offset.y_deg) > kMaxPlausibleZeroOffsetDeg)
    return badInput(fmt::format(
        "inclinometer flip: the readings give a zero offset of ({:.2f}°, {:.2f}°), beyond the "
        "plausible {:g}°: the frame was not turned 180° on the surface, or the surface moved",
        flip.zero.offset.x_deg, flip.zero.offset.y_deg, kMaxPlausibleZeroOffsetDeg));
  flip.uri = readings.first.uri.empty() ? readings.second.uri : readings.first.uri;
  if (flip.uri.empty()) flip.uri = configured_uri;
  if (!configured_uri.empty() && !sameInclinometer(flip.uri, configured_uri))
    spdlog::warn("inclinometer flip: the readings are of {}, the configured sensor is {}", flip.uri,
                 configured_uri);
  const nlohmann::json provenance{{"method", "flip"},
                                  {"date", formatIsoTime(utcNow())},
                                  {"uri", flip.uri},
                                  {"readings", {readings.first.record, readings.second.record}}};
  GLARECAM_CHECK(writeZeroOffset(calibration_file, flip.zero, provenance));
  return flip;
}

}  // namespace glarecam::rig
