// glarecam.calibration/1 (docs/calibration.md): a measured calibration as a versioned artifact.
// Its values use the keys of a stack's calibration block (black_level_dn, saturation_dn,
// luminance_factor, intrinsics, noise, flat_field, ...), so a complete file is accepted wherever
// a block is; on top it names the camera it belongs to and, for each part (dark, flat, noise,
// linearity, luminance, intrinsics), when and how it was measured from which stacks. Each
// `glarecam calibrate` procedure writes one part; `calibrate merge` combines them.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

inline constexpr std::string_view kCalibrationSchema = "glarecam.calibration/1";

struct CameraIdentity {  // empty strings: unknown
  std::string model;
  std::string serial;
  std::string pixel_format;
};

struct PartProvenance {
  std::string measured_at;          // ISO 8601 UTC
  std::string method;               // how, in one line
  std::vector<std::string> inputs;  // the stacks, as given
  // The frames' size it was measured at (absent in files written before glarecam recorded it):
  // parts of one calibration must agree (mergeCalibrationDocuments).
  std::optional<int> width = std::nullopt, height = std::nullopt;
};

struct CalibrationDocument {
  CameraIdentity camera;
  // The block's keys and the parts' extra results (luminance_factor_u, linearity, hot pixels).
  nlohmann::json values = nlohmann::json::object();
  std::map<std::string, PartProvenance> parts;  // by part name
};

// The camera block of a stack manifest ({"model", "serial", "pixel_format"}), where present.
CameraIdentity cameraIdentityOf(const StackManifest& manifest);

Result<CalibrationDocument> parseCalibrationDocument(const nlohmann::json& document,
                                                     const std::string& where);
Result<CalibrationDocument> readCalibrationDocument(const std::filesystem::path& path);
nlohmann::json toJson(const CalibrationDocument& document);
// Atomically, with a trailing newline.
Status writeCalibrationDocument(const std::filesystem::path& path,
                                const CalibrationDocument& document);

// One document from several (read from `files`): values and parts of later documents replace
// earlier ones' (each replacement is reported in `warnings`); the cameras (model, serial, pixel
// format) must agree where both are known. Paths in the values (kPathKeys) become absolute: see
// attachFiles().
Result<CalibrationDocument> mergeCalibrationDocuments(
    std::span<const CalibrationDocument> documents, std::span<const std::filesystem::path> files,
    std::vector<std::string>& warnings);
// Copies the files that absolute paths in the values name into `output_directory` (atomically)
// and makes the values their file names, so the document can be written there.
Status attachFiles(CalibrationDocument& document, const std::filesystem::path& output_directory);

// The values as a stack's calibration block, when they hold every required key; the error names
// the missing parts and `where`.
Result<Calibration> calibrationBlock(const CalibrationDocument& document, const std::string& where);

struct CalibrationUseOptions {
  bool force = false;                // use a calibration made for another camera serial
  double max_age_days = 365;         // older parts are warned about
  std::chrono::sys_days today = {};  // the date ages are counted to; default: today
};

// Whether the calibration may be used for the stack: refuses (kBadInput) one whose camera serial
// differs from the stack's camera serial unless forced, and adds a warning for each part
// measured longer than max_age_days ago. `where` names the calibration's file.
Status checkCalibrationUse(const Calibration& calibration, const StackManifest& manifest,
                           const std::string& where, const CalibrationUseOptions& options,
                           std::vector<std::string>& warnings);

// Keys of `values` that hold paths relative to the calibration file.
inline constexpr std::string_view kPathKeys[] = {"flat_field", "dark_frame", "hot_pixels"};

}  // namespace glarecam::calibration
