// `glarecam calibrate dark`: frames with the lens capped at one or more exposures give the black
// level (the median of the per-pixel mean at the shortest exposure, so that hot pixels and dark
// current do not bias it), the dark frame (the per-pixel mean at the longest exposure), the mean
// dark current (how the levels' medians grow with exposure), its hot-pixel map, and the temporal
// noise at each exposure (from pairs of frames). `process` subtracts the dark frame pixel by pixel
// and masks the hot pixels out of the merge (hdr_merge.h).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

// A hot pixel's dark mean at the longest exposure exceeds the frame's median by this many robust
// standard deviations (a false alarm per ~5e8 normal pixels: none on any sensor we use) ...
inline constexpr double kHotPixelSigmas = 6.0;
// ... and by at least this much, so that a nearly noiseless averaged dark frame does not flag
// pixels one DN of fixed pattern above the rest.
inline constexpr double kMinHotExcessDn = 10.0;
// A frame whose median lies this many DN above the darkest frame's saw light ...
inline constexpr double kLightLeakDn = 50.0;
// ... and so did a frame whose values spread this much across the image (robust sigma): a capped
// sensor's offsets and read noise spread by a few DN, a lit one by its vignetting and scene,
// hundreds.
inline constexpr double kMaxDarkSpreadDn = 25.0;
inline constexpr std::size_t kMinDarkFrames = 2;
// Past this many frames a dark frame's noise is no longer worth chasing: the sensor's pattern is
// below what subtraction can remove.
inline constexpr double kMaxUsefulDarkFrames = 256;

struct DarkLevel {
  double exposure_us = 0;
  std::size_t frames = 0;
  double median_dn = 0;                     // of the per-pixel mean
  std::optional<double> temporal_noise_dn;  // from consecutive pairs; needs two frames
};

struct DarkCalibration {
  double black_level_dn = 0;
  FloatImage dark_frame_dn;  // per-pixel mean at the longest exposure
  double dark_frame_exposure_us = 0;
  double dark_frame_gain_db = 0;  // calibrate dark refuses frames at more than one gain
  // The sensor's mean dark current: the least-squares slope of the levels' medians over exposure
  // (0 with one exposure). `process` moves the dark frame to each frame's exposure with it.
  double dark_current_dn_per_us = 0;
  ByteImage hot_pixels;  // 255 where hot, else 0
  std::size_t hot_pixel_count = 0;
  double hot_threshold_dn = 0;
  std::vector<DarkLevel> levels;  // by exposure
  // What subtracting the dark frame does to a stack: it removes the fixed pattern (the dark
  // frame's spread across pixels, less its own noise) and adds its own noise (the temporal noise
  // over the square root of its frames). Unknown (0) with one frame at the longest exposure.
  double fixed_pattern_dn = 0;
  double dark_frame_noise_dn = 0;
};

// Subtracting a dark frame pays only where the fixed pattern it removes exceeds the noise it adds:
// a warning (with the frames it takes) when it does not, else nothing.
std::optional<std::string> darkFrameNoiseWarning(const DarkCalibration& dark);

// A frame that saw light is named in the error.
Result<DarkCalibration> calibrateDark(std::span<const InputFrame> frames);

// The part's values: black_level_dn, dark frame (with its exposure and the dark current) and
// hot-pixel file names, the levels.
nlohmann::json darkValues(const DarkCalibration& dark, const std::string& dark_frame_file,
                          const std::string& hot_pixels_file);

}  // namespace glarecam::calibration
