// The inclinometer's zero offset by the flip method (docs/rig.md): a reading on a surface near
// level, the sensor's frame turned 180° on the surface into the same outline, a second reading.
// The surface's tilt changes sign between the readings and the sensor's offset does not, so half
// their sum is the offset and half their difference the surface's tilt; the error is second order
// in the surface's tilt, hence the near-level check. The readings may be taken now (with a step
// between them in which the operator turns the frame) or come from saved `inclinometer read
// --out` files. The offset is stored, with both readings as its provenance, in the rig's
// calibration file (zero_offset_file.h).
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "core/error.h"
#include "rig/inclinometer/inclinometer.h"
#include "rig/inclinometer/tilt.h"

namespace glarecam::rig {

// One reading of the flip: the reading, its record as stored in the calibration file (the
// reading's JSON with the sensor's URI and the time), the sensor.
struct FlipReading {
  TiltReading reading;
  nlohmann::json record;
  std::string uri;
};

using FlipReadings = std::pair<FlipReading, FlipReading>;

// The two readings from saved files (`inclinometer read --out`). kBadInput when both name the
// same file or hold the same reading; a warning when they name different sensors.
Result<FlipReadings> savedFlipReadings(const std::filesystem::path& first,
                                       const std::filesystem::path& second);

// Both readings taken now from `sensor` (known as `uri`), each of `options.samples` samples (with
// a progress line on stderr when `show_progress`); `turn` runs between them, once the first
// reading was found near level: it tells the operator to turn the frame and returns when it is
// done (its error ends the calibration).
Result<FlipReadings> takeFlipReadings(Inclinometer& sensor, const std::string& uri,
                                      const TiltOptions& options,
                                      const std::function<Status(const TiltReading& first)>& turn,
                                      bool show_progress = false);

// kBadInput unless the reading is within kMaxPlausibleZeroOffsetDeg of level on both axes.
Status checkNearLevel(const TiltReading& reading);

// The least surface tilt (half the two readings' difference, on either axis) that shows the
// frame was turned. On a level surface a turned frame and an unturned one read the same, so the
// flip cannot tell whether it measured the mounting error or nothing: it asks for a surface
// tilted at least this much (a shim under one side). 0.1° is 25 times the simulated sensor's
// reading noise and 100 times an ADXL355's averaged one (docs/rig.md).
inline constexpr double kMinFlipSurfaceTiltDeg = 0.1;

struct FlipCalibration {
  InclinometerZeroOffset zero;
  std::string uri;           // the sensor the readings are of
  double surface_x_deg = 0;  // the surface's tilt: half the readings' difference
  double surface_y_deg = 0;
};

// The zero offset of `readings`, stored in `calibration_file` with the readings as provenance.
// kBadInput when a reading is not near level, the readings show no turn (surface tilt below
// kMinFlipSurfaceTiltDeg on both axes) or the offset is beyond the plausible (the frame was not
// turned 180°, or the surface moved). `configured_uri`: the rig's sensor, warned about when
// the readings are of another.
Result<FlipCalibration> storeFlipCalibration(const std::filesystem::path& calibration_file,
                                             const FlipReadings& readings,
                                             const std::string& configured_uri);

}  // namespace glarecam::rig
