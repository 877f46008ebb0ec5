// The inclinometer's zero offset lives in the rig's calibration file (the camera calibration's
// JSON, beside `black_level_dn` and the rest) as an `inclinometer` block with its provenance:
//   "inclinometer": { "zero_offset_x_deg": 0.31, "zero_offset_y_deg": -0.12,
//                     "uncertainty_deg": 0.001, "method": "flip", "date": "...", "uri": "...",
//                     "readings": [ {first}, {second} ] }
// Writing merges the block into the file (other keys kept) atomically.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/error.h"
#include "rig/inclinometer/tilt.h"

namespace glarecam::rig {

// A mounting error of tens of degrees is a wrong file, a wrong axis or a flip that was not 180°.
inline constexpr double kMaxPlausibleZeroOffsetDeg = 10.0;

// A reading as JSON (the axis tilts, module tilt, scatter, samples and mean vector), and back:
// the form `glarecam inclinometer read --json` prints and `flip --from` reads.
nlohmann::json tiltReadingJson(const TiltReading& reading);
Result<TiltReading> parseTiltReading(const nlohmann::json& document, const std::string& where);

// nullopt when the file has no `inclinometer` block; an error when the file is missing, is not
// JSON or holds a malformed block (naming the file and key).
Result<std::optional<InclinometerZeroOffset>> readZeroOffset(const std::filesystem::path& file);

// Whether writeZeroOffset() can write `file`: an existing file must be a JSON object, a new one's
// directory must exist and be writable. So that an operator does not flip a sensor for nothing.
Status checkZeroOffsetWritable(const std::filesystem::path& file);

// Sets the file's `inclinometer` block to `zero` with `provenance` merged in (method, date,
// uri, readings); creates the file when absent, refuses to replace one that is not JSON.
Status writeZeroOffset(const std::filesystem::path& file, const InclinometerZeroOffset& zero,
                       const nlohmann::json& provenance);

}  // namespace glarecam::rig
