// The manifest of a recorded stack (glarecam.stack/1, docs/stack-format.md) as value types.
// parseManifest() validates everything that can be checked without the frames and fills the
// documented defaults; toJson() writes it back over the document it came from, so fields this
// version does not know survive a read-modify-write. Units are in the field names.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/source_illuminance.h"

namespace glarecam {

inline constexpr std::string_view kStackSchema = "glarecam.stack/1";
inline constexpr std::string_view kManifestFileName = "stack.json";

// Pinhole camera + OpenCV distortion (k1, k2, p1, p2, k3), in pixels.
struct Intrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::array<double, 5> distortion{};
  // The image size they were calibrated at (`glarecam calibrate intrinsics` records it; older
  // files and other tools may not): in pixels of another size every angle is wrong.
  std::optional<int> width = std::nullopt, height = std::nullopt;
};

// Sensor noise at gain 0 dB: temporal read noise and conversion gain.
struct NoiseModel {
  double read_noise_dn = 0;
  double dn_per_electron = 0;
};

struct Calibration {
  double black_level_dn = 0;
  double saturation_dn = 0;
  double luminance_factor = 0;  // K: cd/m² per (DN/µs) at the reference f-number
  std::optional<double> reference_f_number;
  Intrinsics intrinsics;
  std::optional<std::string> flat_field;  // path relative to the calibration's directory
  // The dark frame (`glarecam calibrate dark`): the per-pixel mean of capped frames at
  // dark_frame_exposure_us, subtracted per pixel in place of black_level_dn; the sensor's mean dark
  // current (DN/µs, from the dark levels' medians) moves it to each frame's exposure. Hot pixels:
  // a PNG, non-zero where hot, masked out of the merge. Paths as flat_field's.
  std::optional<std::string> dark_frame;
  std::optional<double> dark_frame_exposure_us;
  double dark_frame_gain_db = 0;  // the gain it was taken at: frames at another gain do not use it
  double dark_current_dn_per_us = 0;
  std::optional<std::string> hot_pixels;
  std::optional<NoiseModel> noise;
  nlohmann::json source = nlohmann::json::object();  // the block as read, unknown keys kept
  // Where its relative image paths start, absolute: the file's directory for a calibration read
  // from a file (readCalibrationFile), empty for a stack's inline block (the stack's directory).
  // Not written: a capture copies the images into the stack instead (capture/bracketer.h).
  std::filesystem::path directory;
};

struct FrameSpec {
  std::string file;
  double exposure_us = 0;
  double gain_db = 0;
  std::optional<double> f_number;  // absent: the calibration's reference f-number
  double nd_transmission = 1;
  nlohmann::json source = nlohmann::json::object();
};

struct StackManifest {
  std::optional<std::string> id;
  std::optional<std::string> captured_at;
  std::optional<double> alpha_deg;
  std::optional<Calibration> calibration;       // given inline
  std::optional<std::string> calibration_path;  // or as a path relative to the stack
  std::vector<FrameSpec> frames;
  // The manifest's `source` block: the illuminance that lit the stack; absent: unreferred.
  std::optional<SourceIlluminance> source_illuminance;
  nlohmann::json source = nlohmann::json::object();  // camera, geometry, unknown keys
};

// `where` names the file in error messages.
Result<StackManifest> parseManifest(const nlohmann::json& document, const std::string& where);
Result<Calibration> parseCalibration(const nlohmann::json& block, const std::string& where);

nlohmann::json toJson(const Calibration& calibration);

// The keys of a calibration block that name an image file (flat_field, dark_frame, hot_pixels),
// with their relative paths, in that order; absent ones left out.
std::vector<std::pair<std::string, std::string>> calibrationImages(const Calibration& calibration);
// Sets the image path `key` (one of calibrationImages') to `path`.
void setCalibrationImage(Calibration& calibration, const std::string& key, const std::string& path);
nlohmann::json toJson(const StackManifest& manifest);

// A manifest's alpha_deg lies in [0, kMaxStackAlphaDeg]: the angle from the module normal.
inline constexpr double kMaxStackAlphaDeg = 90.0;

// Largest image side a calibration may name, in pixels (the sim camera's URI bound, far above
// any sensor): keeps a recorded width or height an int.
inline constexpr int kMaxImageSide = 1 << 20;

// An image side a calibration may record: a whole number of pixels in [1, kMaxImageSide].
bool isImageSidePx(double value);

// True when `relative` is a plain relative path that stays inside its base directory.
bool isContainedRelativePath(std::string_view relative);

}  // namespace glarecam
